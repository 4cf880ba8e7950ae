"""
A truss and its bilateration plan
=================================

Thesis §3.4.1's nine-link truss 9/B28: its structural diagram (ternary links grey, binary
links as bars), and the order in which its best bilateration plan places the joints. The
reference pair sits at 0 and 1; each step places a joint from two placed ones; the
dashed lines are the plan's two parameters (unknown squared distances: coupling degree
2), the dotted ones its two closure pairs, whose computed distances must equal the link
dimensions.
"""

import matplotlib.pyplot as plt
from matplotlib.patches import Polygon

import baranov
from baranov.topology import diagram_layout, joints_of_links
from baranov.topology.diagram import convex_hull

chain = baranov.truss("9/B28")
plan = baranov.best_plan(chain)
at = diagram_layout(chain)

figure, axis = plt.subplots(figsize=(7, 7))
for names in joints_of_links(chain):
    points = [at[name] for name in names]
    if len(points) > 2:
        axis.add_patch(Polygon(convex_hull(points), closed=True, facecolor="0.82", edgecolor="0.15", linewidth=1.5))
    else:
        axis.plot(*zip(*points, strict=True), color="0.15", linewidth=4, solid_capstyle="round")
for pairs, style, label in ((plan.parameters, "--", "parameter"), (plan.closure_pairs, ":", "closure pair")):
    for number, (u, v) in enumerate(pairs):
        axis.plot(*zip(at[u], at[v], strict=True), style, color="tab:red" if style == "--" else "tab:blue",
                  linewidth=2, label=label if number == 0 else None)
order = {joint: 0 for joint in plan.reference} | {step.joint: n for n, step in enumerate(plan.steps, 1)}
for joint, (x, y) in at.items():
    axis.plot(x, y, "o", markersize=18, markerfacecolor="white", markeredgecolor="0.1")
    axis.annotate(f"{joint}\n{order[joint]}", (x, y), ha="center", va="center", fontsize=7)
axis.set_aspect("equal")
axis.set_axis_off()
axis.legend(loc="lower right")
axis.set_title(f"9/B28: reference {', '.join(plan.reference)} (step 0), then steps 1–{len(plan.steps)}")
plt.show()

# %%
# The plan's steps and closure conditions, as ``baranov show 9/B28`` prints them.
for number, step in enumerate(plan.steps, 1):
    print(number, step.joint, "from", ", ".join(step.base), step.kind.name.lower(),
          "(free sign)" if step.free_sign else "")
print(baranov.closure_system(plan).text())
