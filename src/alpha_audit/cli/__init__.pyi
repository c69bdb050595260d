from .root import (
    app as app,
    main as main,
)
from .status import (
    ExitStatus as ExitStatus,
)
