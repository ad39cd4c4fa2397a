import os
import sys

from hypothesis import HealthCheck, settings

sys.path.insert(0, os.path.dirname(__file__))

# Modest example counts: the whole Python stage must stay within a few minutes on 2 cores.
settings.register_profile(
    "ci",
    max_examples=int(os.environ.get("TOPOPLEX_PY_EXAMPLES", "50")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile("ci")
