"""The repository's examples/ folder, wherever a gallery script is run from."""

from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
