from .audit import (
    page_audits as page_audits,
    page_report as page_report,
)
from .config import (
    RenderConfig as RenderConfig,
    config_from_yaml as config_from_yaml,
    source_from_argument as source_from_argument,
)
from .run import (
    audit_pages as audit_pages,
)
from .sources import (
    FolderSource as FolderSource,
    StorybookSource as StorybookSource,
    UrlSource as UrlSource,
)
from .states import (
    State as State,
    state_matrix as state_matrix,
)
