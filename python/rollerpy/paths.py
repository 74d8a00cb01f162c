"""Where the checkout's folders are, for the commands' defaults (the package lives in python/)."""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PROBLEMS = os.path.join(ROOT, "problems")
# The program pip installed beside the package (python/setup.py), else the checkout's build.
_INSTALLED_ROLLER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "roller")
DEFAULT_ROLLER = _INSTALLED_ROLLER if os.path.isfile(_INSTALLED_ROLLER) else os.path.join(ROOT, "build", "roller")
