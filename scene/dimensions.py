"""A scene's dimensions by name, and the scene with some of them replaced: the instances
of a parameter sweep or a batch (issue 21), where one topology is solved for many link
dimensions.

A dimension is the squared distance s_{u,v} of two joints on one moving link, named
``"Pu,Pv"`` as in a scene file's ``"squared_distances"``. The fixed link's dimensions are
its joints' coordinates and are not varied here (a sweep of the fixed link moves the
world frame; give the scene anew).
"""

from __future__ import annotations

import csv
import json
from collections.abc import Mapping
from dataclasses import replace
from decimal import Decimal
from pathlib import Path

from .model import Scene, SceneError, SceneLink, _number, _parse_link
from .numbers import Number


def dimension_names(scene: Scene) -> list[str]:
    """The dimensions of the scene's moving links, ``"Pu,Pv"`` (joints in the link's
    order), link by link in scene order: the columns a batch may vary.

    >>> from baranov.scene import load_scene
    >>> dimension_names(load_scene("examples/7-B1.json"))[:3]
    ['P2,P4', 'P2,P7', 'P4,P7']
    """
    names = []
    for link in scene.links:
        if link.name != scene.ground:
            names += [f"{a},{b}" for k, a in enumerate(link.joints) for b in link.joints[k + 1:]]
    return names


def link_entry(link: SceneLink) -> dict:
    """The scene-file entry of ``link`` by its squared distances (exact numbers as strings
    such as ``"9/5"``, so that reading it back is exact) and, for three joints or more, the
    orientation of its first three joints in its own frame."""
    entry = {"name": link.name, "joints": list(link.joints),
             "squared_distances": {f"{a},{b}": str(link.squared_distances[frozenset((a, b))])
                                   for k, a in enumerate(link.joints) for b in link.joints[k + 1:]}}
    if len(link.joints) >= 3:
        (x1, y1), (x2, y2), (x3, y3) = (link.local[name] for name in link.joints[:3])
        entry["orientation"] = "ccw" if (x2 - x1) * (y3 - y1) - (y2 - y1) * (x3 - x1) > 0 else "cw"
    return entry


def with_dimensions(scene: Scene, dimensions: Mapping) -> Scene:
    """``scene`` with the squared distances ``dimensions`` (``{"P1,P2": 17, ...}``; a key
    may also be a pair of joint names) in place of its own; every other dimension, the
    fixed link, the orientation of each link's first three joints, sliders and inputs stay.
    Integers, fractions, decimals and strings such as ``"9/5"`` keep the scene exact; a
    float makes it inexact (:mod:`baranov.scene.model`).

    Raises :class:`~baranov.scene.SceneError` naming the pair for joints on no common
    link or on the fixed link, and naming the link for dimensions that no planar link has
    (the triangle inequality, a body's Cayley–Menger check).

    >>> from baranov.scene import load_scene
    >>> scene = load_scene("examples/7-B1.json")
    >>> str(with_dimensions(scene, {"P2,P4": 20}).known[frozenset(("P2", "P4"))])
    '20'
    """
    links = {link.name: link for link in scene.links}
    changed: dict[str, dict[frozenset[str], Number]] = {}
    for key, value in dimensions.items():
        pair = _pair(key)
        link = next((link for link in scene.links if pair <= set(link.joints)), None)
        text = ",".join(sorted(pair))
        if link is None:
            raise SceneError(f"dimension {text}: joints on no common link (a dimension is the squared distance of "
                             "two joints of one link)")
        if link.name == scene.ground:
            raise SceneError(f"dimension {text}: on the fixed link {link.name}, whose dimensions are its joints' "
                             "coordinates; vary a moving link's, or give the scene anew")
        changed.setdefault(link.name, {})[pair] = _number(value, f"link {link.name}, squared distance {text}")
    exact = scene.exact
    for name, values in changed.items():
        entry = link_entry(links[name])
        for pair, value in values.items():
            a, b = (joint for joint in links[name].joints if joint in pair)
            entry["squared_distances"][f"{a},{b}"] = value  # a Fraction or a float: the link's own check reads it
        index = [link.name for link in scene.links].index(name)
        links[name], _, link_exact = _parse_link(entry, index)  # exact: every squared distance a Fraction
        exact = exact and link_exact
    return replace(scene, links=tuple(links[link.name] for link in scene.links), exact=exact)


def load_instances(path: str | Path) -> list[dict[str, object]]:
    """The instances of a batch file: CSV with a header of dimension names (``P1,P2`` needs
    quotes in CSV: ``"P1,P2"``) and one instance per row, or JSON lines (``.jsonl``), one
    object ``{"P1,P2": 17, ...}`` per line. Numbers stay as written (a CSV field and a JSON
    decimal are exact: ``2.5`` is 5/2), for :func:`with_dimensions` to read; blank lines
    are skipped.

    Raises :class:`~baranov.scene.SceneError` naming the file and line."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as error:
        raise SceneError(f"{path}: cannot read ({error.strerror})") from None
    if path.suffix.lower() == ".csv":
        rows = [row for row in csv.reader(text.splitlines()) if any(field.strip() for field in row)]
        if not rows:
            raise SceneError(f"{path}: empty; the first line names the dimensions, e.g. \"P1,P2\",\"P3,P4\"")
        header, instances = [name.strip() for name in rows[0]], []
        for number, row in enumerate(rows[1:], start=2):
            if len(row) != len(header):
                raise SceneError(f"{path}, row {number}: {len(row)} values for {len(header)} columns")
            instances.append(dict(zip(header, (field.strip() for field in row), strict=True)))
        return instances
    instances = []
    for number, line in enumerate(text.splitlines(), start=1):
        if line.strip():
            try:
                instance = json.loads(line, parse_float=Decimal)
            except ValueError as error:
                raise SceneError(f"{path}, line {number}: not valid JSON ({error})") from None
            if not isinstance(instance, dict):
                raise SceneError(f"{path}, line {number}: expected an object such as {{\"P1,P2\": 17}}")
            instances.append(instance)
    return instances


def _pair(key) -> frozenset[str]:
    parts = [part.strip() for part in key.split(",")] if isinstance(key, str) else list(key)
    if len(parts) != 2 or parts[0] == parts[1]:
        raise SceneError(f"dimension {key!r}: should name two joints, e.g. \"P1,P2\"")
    return frozenset(str(part) for part in parts)
