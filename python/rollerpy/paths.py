"""Where the checkout's folders are, for the commands' defaults (the package lives in python/)."""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PROBLEMS = os.path.join(ROOT, "problems")
DEFAULT_ROLLER = os.path.join(ROOT, "build", "roller")
