"""Per-face stiffness and width factors from Blender vertex-group weights, and back.

A weight of 0.5 is neutral (factor 1), as Weight Paint's green; 0 and 1 are the ends of the
editor's paint ranges (docs/editor.md, "Painting"): stiffness from x0.05 to x4 on a logarithmic
scale, width from x0.5 to x1.5 linearly. A vertex outside the group counts as 0.5. A face takes
the factor of its corner nearest to neutral, so a painted region ends at its own faces and a
face becomes stiffer or softer only where all its corners were painted. Factors are kept to
hundredths, as the editor keeps blended values, so a painted layer saves as a few regions.
"""

import math

import numpy as np

STIFFNESS_RANGE = (0.05, 4.0)
WIDTH_RANGE = (0.5, 1.5)


def stiffness_factor(weight):
    w = np.asarray(weight, dtype=np.float64)
    low, high = STIFFNESS_RANGE
    return np.where(w < 0.5, np.exp(math.log(low) * (1.0 - 2.0 * w)), np.exp(math.log(high) * (2.0 * w - 1.0)))


def stiffness_weight(factor):
    f = np.clip(np.asarray(factor, dtype=np.float64), *STIFFNESS_RANGE)
    low, high = STIFFNESS_RANGE
    return np.where(f < 1.0, 0.5 * (1.0 - np.log(f) / math.log(low)), 0.5 * (1.0 + np.log(f) / math.log(high)))


def width_factor(weight):
    return WIDTH_RANGE[0] + np.asarray(weight, dtype=np.float64) * (WIDTH_RANGE[1] - WIDTH_RANGE[0])


def width_weight(factor):
    f = np.clip(np.asarray(factor, dtype=np.float64), *WIDTH_RANGE)
    return (f - WIDTH_RANGE[0]) / (WIDTH_RANGE[1] - WIDTH_RANGE[0])


def face_weights(vertex_weights, face_vertices, face_starts):
    """Each face's corner weight nearest to 0.5: its lowest when all corners are at or above
    0.5, its highest when all are at or below, else 0.5 (neutral lies between its corners).
    `face_vertices` lists the faces' corners one after another, face f's from face_starts[f]
    (Blender's loops)."""
    corner = np.asarray(vertex_weights, dtype=np.float64)[face_vertices]
    lowest = np.minimum.reduceat(corner, face_starts)
    highest = np.maximum.reduceat(corner, face_starts)
    return np.where(lowest >= 0.5, lowest, np.where(highest <= 0.5, highest, 0.5))


def face_factors(vertex_weights, face_vertices, face_starts, to_factor):
    return np.round(to_factor(face_weights(vertex_weights, face_vertices, face_starts)), 2)


def vertex_weights_for(face_factor, face_vertices, face_starts, n_vertices, to_weight):
    """Weights that give back `face_factor` (rounded to hundredths) on every face painted
    uniformly, for a scenario's regions: each vertex of a face with a factor other than 1 takes
    that face's weight, later faces winning; every other vertex is neutral."""
    weights = np.full(n_vertices, 0.5)
    counts = np.diff(np.append(face_starts, len(face_vertices)))
    per_corner = np.repeat(np.asarray(face_factor, dtype=np.float64), counts)
    painted = per_corner != 1.0
    weights[np.asarray(face_vertices)[painted]] = to_weight(per_corner[painted])
    return weights
