// Many real Lucide icons at 16 and 24 px in the themes' roles, and a failure by opacity.
// The icons: lucide-static 1.62.0's icon names (icon-nodes.json), sorted, every 39th:
// 48 distinct icons, chosen by that rule and not for how they draw.
import {
  AArrowDown, Amphora, ArrowRight, BadgeEuro, Bed, Bell, Bone, BowArrow, Calendar1, CardSim,
  CheckLine, CircleChevronDown, CircleUserRound, ClockFading, Computer, Crown, Dna,
  EmiratiDirham, FileChartLine, FileTypeCorner, FolderCog, GalleryHorizontalEnd, GlobeLock,
  HardDriveUpload, HouseCog, KeyboardOff, LensConvex, ListStart, MapPinCheck, MessageSquare,
  MonitorCloud, MoveHorizontal, PackagePlus, PcCase, Plane, RadioReceiver, ReplyAll, SaveOff,
  Search, Server, ShoppingCartPlus, Sparkle, SquareChevronLeft, SquareScissors, StickyNoteX,
  Tally2, TicketX, Triangle, UserLock, VideoOff,
} from "lucide-static";

const ICONS = {
  "a-arrow-down": AArrowDown, amphora: Amphora, "arrow-right": ArrowRight,
  "badge-euro": BadgeEuro, bed: Bed, bone: Bone, "bow-arrow": BowArrow, "calendar-1": Calendar1,
  "card-sim": CardSim, "check-line": CheckLine, "circle-chevron-down": CircleChevronDown,
  "circle-user-round": CircleUserRound, "clock-fading": ClockFading, computer: Computer,
  crown: Crown, dna: Dna, "emirati-dirham": EmiratiDirham, "file-chart-line": FileChartLine,
  "file-type-corner": FileTypeCorner, "folder-cog": FolderCog,
  "gallery-horizontal-end": GalleryHorizontalEnd, "globe-lock": GlobeLock,
  "hard-drive-upload": HardDriveUpload, "house-cog": HouseCog, "keyboard-off": KeyboardOff,
  "lens-convex": LensConvex, "list-start": ListStart, "map-pin-check": MapPinCheck,
  "message-square": MessageSquare, "monitor-cloud": MonitorCloud,
  "move-horizontal": MoveHorizontal, "package-plus": PackagePlus, "pc-case": PcCase,
  plane: Plane, "radio-receiver": RadioReceiver, "reply-all": ReplyAll, "save-off": SaveOff,
  server: Server, "shopping-cart-plus": ShoppingCartPlus, sparkle: Sparkle,
  "square-chevron-left": SquareChevronLeft, "square-scissors": SquareScissors,
  "sticky-note-x": StickyNoteX, "tally-2": Tally2, "ticket-x": TicketX, triangle: Triangle,
  "user-lock": UserLock, "video-off": VideoOff,
};
// Each icon's role: its colour and backdrop (.storybook/theme.css); the id names both.
const ROLES = ["plain", "accent", "chip"];

const icon = (svg, name, size, role) =>
  svg
    .replace("<svg", `<svg id="${role}-${size}-${name}" data-icon="${name}"`)
    .replace('width="24"', `width="${size}"`)
    .replace('height="24"', `height="${size}"`);

export default { title: "Gallery" };

export const Lucide = {
  render: () => `<div class="gallery">${[16, 24]
    .flatMap((size, row) =>
      Object.entries(ICONS).map(([name, svg], k) => {
        const role = ROLES[(k + row) % ROLES.length];
        return `<span class="${role}">${icon(svg, name, size, role)}</span>`;
      }),
    )
    .join("")}</div>`,
};

// A passing colour made to fail by its wrapper: opacity 0.5 halves its difference from the surface.
export const Faded = {
  render: () => `<div class="toolbar"><span class="faded">
    ${icon(Bell, "bell", 24, "faded")}${icon(Search, "search", 16, "faded")}
  </span></div>`,
};
