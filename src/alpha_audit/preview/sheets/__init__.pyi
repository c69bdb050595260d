from .pages import (
    MAX_SHEETS as MAX_SHEETS,
    paginate as paginate,
)
from .plan import (
    ICON_ALPHA as ICON_ALPHA,
    SWATCH_ALPHAS as SWATCH_ALPHAS,
    Alpha as Alpha,
    ImageFormat as ImageFormat,
    Layout as Layout,
    Page as Page,
    SheetSpec as SheetSpec,
    default_alphas as default_alphas,
    plan_sheets as plan_sheets,
)
from .render import (
    render_all as render_all,
    render_sheet as render_sheet,
)
from .surface import (
    PIXEL_BUDGET as PIXEL_BUDGET,
    Placement as Placement,
    Sheet as Sheet,
)
from .write import (
    check_writable as check_writable,
    write_sheet as write_sheet,
)
