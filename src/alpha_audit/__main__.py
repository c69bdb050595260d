"""``python -m alpha_audit``: the same as the ``alpha-audit`` command."""

from alpha_audit.cli import main

if __name__ == "__main__":
    main()
