"""Files in, previews out: what ``alpha-audit preview`` does, callable from Python."""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path

from alpha_audit.color import GamutPolicy, Pipeline
from alpha_audit.errors import SvgError, UsageError
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.paint_masks import paint_masks
from alpha_audit.load.theme import load_theme
from alpha_audit.model import Canvas, IconProblem, IconSet, Theme
from alpha_audit.output import make_folder, write_text
from alpha_audit.preview.compose import near_source_canvases
from alpha_audit.preview.figures import preview_rows
from alpha_audit.preview.html import preview_html
from alpha_audit.preview.sheets import (
    SWATCH_ALPHAS,
    Alpha,
    ImageFormat,
    Layout,
    Sheet,
    SheetSpec,
    check_writable,
    default_alphas,
    paginate,
    plan_sheets,
    render_all,
    write_sheet,
)
from alpha_audit.ranges import ALPHA, ICON_SIZE
from alpha_audit.results import Progress
from alpha_audit.rows import check_pipeline, resolve_pipeline

__all__ = ["DEFAULT_SIZE", "PreviewResult", "preview_canvases", "preview_files"]

DEFAULT_SIZE = 48  # px, the paper's gallery and timing size (Appendix A.2)


@dataclass(frozen=True)
class PreviewResult:
    """Files written, in order, and the icons that could not be rendered."""

    written: tuple[Path, ...]
    problems: tuple[IconProblem, ...]


def preview_canvases(theme: Theme, iconset: IconSet, near_source: bool) -> tuple[Canvas, ...]:
    """The theme's canvases, or the paper's near-source canvases for the set's palette."""
    if not near_source:
        return theme.canvases
    palette = iconset.palette or {i.color_name or i.color: i.color for i in iconset.icons}
    return near_source_canvases(palette, path=iconset.path)


def _check_options(
    out_dir: str | Path | None,
    html_path: str | Path | None,
    alphas: Sequence[float],
    sizes: Sequence[int],
    image_format: ImageFormat,
) -> None:
    """Refuse options that cannot work, before any file is read."""
    if out_dir is None and html_path is None:
        raise UsageError("nothing to write: give `out_dir` for PNG sheets and/or `html_path`")
    # The ranges the command line's --alpha and --size obey, in the same words.
    for name, values, allowed in (("alphas", alphas, ALPHA), ("sizes", sizes, ICON_SIZE)):
        for value in values:
            if value not in allowed:
                raise UsageError(allowed.refusal(f"`{name}` {value:g}"))
    if out_dir is not None and image_format is ImageFormat.WEBP:
        from PIL import features

        if not features.check("webp"):
            raise UsageError("this Pillow was built without WebP; write PNG sheets instead")


def _load(
    theme_path: str | Path,
    iconset_path: str | Path,
    gamut: GamutPolicy | None,
    threshold: float | None,
    pipeline: str | None,
    alphas: Sequence[float],
    near_source: bool,
) -> tuple[Theme, IconSet, Pipeline]:
    """The theme (with ``threshold``, and its canvases as the rows see them: translucent
    layers composited as the pipeline draws), the icon set and the pipeline they are
    drawn in, refused if that pipeline cannot draw an icon at one of ``alphas``."""
    theme = load_theme(theme_path, gamut=gamut)
    iconset = load_iconset(iconset_path, gamut=gamut)
    if threshold is not None:
        theme = replace(theme, threshold=float(threshold))
    kind = resolve_pipeline(pipeline, iconset.pipeline, theme.pipeline)
    check_pipeline(iconset, kind)
    for a in alphas:
        check_pipeline(iconset, kind, a)
    shown = replace(theme, canvases=preview_canvases(theme, iconset, near_source))
    return replace(theme, canvases=shown.flattened(kind).canvases), iconset, kind


def _usable(iconset: IconSet, problems: Sequence[IconProblem], strict_svg: bool) -> IconSet:
    """The icons that rendered; with ``strict_svg`` the first that did not is an error."""
    if strict_svg and problems:
        raise SvgError(problems[0].message, path=problems[0].file)
    return iconset.without({p.icon for p in problems})


def preview_files(
    theme_path: str | Path,
    iconset_path: str | Path,
    *,
    out_dir: str | Path | None = None,
    html_path: str | Path | None = None,
    layout: Layout = Layout.GRID,
    alphas: Sequence[float] = (),
    sizes: Sequence[int] = (),
    near_source: bool = False,
    threshold: float | None = None,
    overwrite: bool = False,
    strict_svg: bool = False,
    progress: Progress | None = None,
    gamut: GamutPolicy | None = None,
    pipeline: str | None = None,
    image_format: ImageFormat = ImageFormat.PNG,
) -> PreviewResult:
    """Load, render every paint group once, audit, then write sheets and/or a page.

    Sheets go to ``out_dir``, the page to ``html_path``.  Icons are drawn as
    their audit rows draw them (each paint group in its colour and opacity,
    under ``pipeline``: the given one, else the icon set's, else the
    theme's, else linear, as ``check`` decides) and labelled with their
    rows' size contrast.  Every target is checked before any work: an
    existing file is an error unless ``overwrite``.  ``progress`` (start,
    advance) is told the icons to render plus the files to write, then each;
    ``gamut`` decides colours outside sRGB (else each file's ``gamut:``,
    else they are an error).  Sheets are PNG files, or lossless WebP with
    ``image_format``.
    """
    _check_options(out_dir, html_path, alphas, sizes, image_format)
    theme, iconset, kind = _load(
        theme_path, iconset_path, gamut, threshold, pipeline, alphas, near_source
    )
    sheet_sizes = sorted(set(sizes)) if sizes else [DEFAULT_SIZE]
    page_sizes = sorted(set(sizes)) if sizes else sorted({*iconset.sizes, DEFAULT_SIZE})
    prefix = "near-source" if near_source else theme.name
    title = f"{iconset.name} on {'near-source canvases' if near_source else theme.name}"

    specs = []
    if out_dir is not None:
        specs = paginate(
            plan_sheets(layout, theme.canvases, sheet_sizes, prefix),
            iconset,
            alphas=list(alphas) or None,
            threshold=theme.threshold,
            title=title,
            source=iconset.path if near_source else theme.path,
        )
    _check_targets(specs, out_dir, html_path, image_format, overwrite)
    step: Callable[[], None] = _nothing if progress is None else progress[1]
    raster_sizes = sorted({*(sheet_sizes if specs else ()), *(page_sizes if html_path else ())})
    if progress is not None:
        progress[0](len(iconset.icons) + len(specs) + (html_path is not None))
    masks = paint_masks([(i.name, i.file) for i in iconset.icons], raster_sizes, progress=step)
    usable = _usable(iconset, masks.problems, strict_svg)
    rows: list[Alpha] = list(alphas) if alphas else default_alphas(usable)
    # css opacity stops at 1: the swatch rows it can draw (the others are the linear pipeline's).
    swatch_rows = [a for a in SWATCH_ALPHAS if 0.0 <= a <= 1.0] if kind == "css" else None
    drawn = preview_rows(theme, iconset, masks, raster_sizes, kind)

    sheets = render_all(
        specs,
        iconset,  # pages index the manifest's icons; icons not drawn are left out
        drawn,
        alphas=rows if (alphas or layout is not Layout.SWATCHES) else swatch_rows,
        threshold=theme.threshold,
        title=title,
    )
    save = partial(
        write_sheet, folder=out_dir or ".", overwrite=overwrite, image_format=image_format
    )
    written = _write_sheets(sheets, save, step)
    if html_path is not None:
        alpha = alphas[0] if alphas else None
        page = preview_html(theme, usable, drawn, sizes=page_sizes, alpha=alpha)
        written.append(write_text(html_path, page, overwrite=overwrite))
        step()
    return PreviewResult(tuple(written), masks.problems)


def _nothing() -> None:
    """No progress to report."""


def _check_targets(
    specs: Sequence[SheetSpec],
    out_dir: str | Path | None,
    html_path: str | Path | None,
    image_format: ImageFormat,
    overwrite: bool,
) -> None:
    """Every file the preview will write, checked before any work (the folder made)."""
    targets: list[Path] = []
    if out_dir is not None:
        folder = Path(out_dir)
        if folder.exists() and not folder.is_dir():
            raise UsageError("is not a folder", path=folder)
        targets += [folder / image_format.file_name(s.name) for s in specs]
    if html_path is not None:
        targets.append(Path(html_path))
    if out_dir is not None:
        make_folder(out_dir)
    check_writable(targets, overwrite=overwrite)


def _write_sheets(
    sheets: Iterable[Sheet], save: Callable[[Sheet], Path], step: Callable[[], None]
) -> list[Path]:
    """Each sheet saved on a second thread while the next one is drawn (Pillow's encoder
    and numpy release the GIL); at most two sheets are held at once."""
    written: list[Path] = []
    pending: deque[Future[Path]] = deque()

    def collect() -> None:
        written.append(pending.popleft().result())
        step()

    with ThreadPoolExecutor(max_workers=1, thread_name_prefix="alpha-audit-sheet") as writer:
        for sheet in sheets:
            pending.append(writer.submit(save, sheet))
            if len(pending) > 1:
                collect()
        while pending:
            collect()
    return written
