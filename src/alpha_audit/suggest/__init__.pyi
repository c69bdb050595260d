from .engine import (
    largest_safe_alpha as largest_safe_alpha,
    suggest as suggest,
)
from .scope import (
    SCOPES as SCOPES,
)
