"""An animation of a linkage moving along one branch of its driven motion
(:mod:`.driving`): one frame per input value, the linkage drawn as ``baranov solve --plot``
draws an assembly mode, the tracers' paths so far behind it."""

from __future__ import annotations

import tempfile
from pathlib import Path

from baranov.scene import Scene
from baranov.solvers.drawing import draw_mode

from .driving import DrivenBranch


def render_animation(scene: Scene, branch: DrivenBranch, tracers: list[str], input_name: str,
                     unit: str = "", milliseconds: int = 120) -> bytes:
    """A GIF of ``scene`` at every configuration of ``branch`` in order (``milliseconds``
    per frame), the paths of ``tracers`` drawn up to the frame, the input's value in the
    title. The view is fixed: it holds every frame. Cost: one drawing per frame."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter

    xs = [x for point in branch.points for x, _ in point.joints.values()]
    ys = [y for point in branch.points for _, y in point.joints.values()]
    extent = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    margin = 0.08 * extent
    figure, axis = plt.subplots(figsize=(5, 5), dpi=80)

    def frame(number: int) -> None:
        axis.clear()
        point = branch.points[number]
        for tracer in tracers:
            path = [p.joints[tracer] for p in branch.points[:number + 1]]
            axis.plot([x for x, _ in path], [y for _, y in path], color="tab:blue", linewidth=1.2, zorder=2.5)
        draw_mode(axis, scene, point, extent)
        axis.set_xlim(min(xs) - margin, max(xs) + margin)
        axis.set_ylim(min(ys) - margin, max(ys) + margin)
        axis.set_aspect("equal")
        axis.set_title(f"from piece {branch.piece}, {input_name} = {branch.values[number]:.4g}{unit} "
                       f"({number + 1}/{len(branch.points)})", fontsize=10)

    animation = FuncAnimation(figure, frame, frames=len(branch.points))
    with tempfile.TemporaryDirectory(prefix="baranov-animation-") as folder:
        target = Path(folder) / "motion.gif"
        animation.save(target, writer=PillowWriter(fps=max(1, round(1000 / milliseconds))), dpi=80)
        plt.close(figure)
        return target.read_bytes()
