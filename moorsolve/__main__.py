"""`python -m moorsolve` runs the command line, as the `moorsolve` script does."""

from .cli import main

raise SystemExit(main())
