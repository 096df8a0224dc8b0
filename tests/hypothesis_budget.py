"""How many hypothesis examples a test runs: modest by default, more on request.

``MOORSOLVE_HYPOTHESIS_PROFILE=thorough python -m pytest`` multiplies every budget given
through :func:`examples` by :data:`THOROUGH_FACTOR` (README, "Testing").
"""

import os

PROFILE = os.environ.get("MOORSOLVE_HYPOTHESIS_PROFILE", "default")
THOROUGH_FACTOR = 20
if PROFILE not in ("default", "thorough"):
    raise ValueError(f"MOORSOLVE_HYPOTHESIS_PROFILE={PROFILE!r}: use 'default' or 'thorough'")


def examples(n: int) -> int:
    """The example budget for a test whose default is ``n``."""
    return n * THOROUGH_FACTOR if PROFILE == "thorough" else n
