"""The repository and its examples/ folder, wherever a gallery script is run from."""

from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]
EXAMPLES = REPOSITORY / "examples"
