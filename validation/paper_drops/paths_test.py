#!/usr/bin/python3
"""Tests of validation/paper_drops/paths.py (ctest paper_paths_py_test): the path measures on paths
whose answer is known by construction."""
import math
import os
import sys
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paths  # noqa: E402

Z = np.linspace(1.0, 0.0, 201)   # 1 m of descent


class PathsTest(unittest.TestCase):
    def test_a_straight_glide_is_straight_and_planar(self):
        x, y = 0.3 * (1 - Z), 0.4 * (1 - Z)   # 0.5 m sideways along a fixed heading
        s, per_m, net = paths.path_measures(x, y, Z)
        self.assertAlmostEqual(s, 1.0, places=12)
        self.assertAlmostEqual(per_m, 0.5, places=12)
        self.assertAlmostEqual(net, 0.5, places=12)
        self.assertLess(paths.planarity(x, y), 1e-6)

    def test_a_zigzag_in_one_plane_is_planar_but_not_straight(self):
        # four swings of amplitude 0.1 m along x: 0.8 m of path, back where it started
        x = 0.1 * np.sin(2 * math.pi * 2 * (1 - Z))
        s, per_m, net = paths.path_measures(x, 0 * x, Z)
        self.assertAlmostEqual(per_m, 0.8, delta=0.01)
        self.assertLess(net, 1e-9)
        self.assertLess(s, 1e-8)
        self.assertEqual(paths.planarity(x, 0 * x), 0.0)

    def test_a_circle_wanders_equally_in_every_direction(self):
        a = np.linspace(0, 2 * math.pi, 400, endpoint=False)
        x, y = 0.2 * np.cos(a), 0.2 * np.sin(a)
        self.assertAlmostEqual(paths.planarity(x, y), 1.0, places=6)
        s, per_m, _ = paths.path_measures(x, y, np.linspace(1.0, 0.0, 400))
        self.assertLess(s, 0.01)                              # nearly back at the start
        self.assertAlmostEqual(per_m, 2 * math.pi * 0.2, delta=0.01)

    def test_a_vertical_fall_and_a_short_path(self):
        self.assertEqual(paths.path_measures(0 * Z, 0 * Z, Z)[0], 1.0)
        self.assertEqual(paths.planarity(0 * Z, 0 * Z), 0.0)
        self.assertTrue(math.isnan(paths.planarity([0.0, 1.0], [0.0, 1.0])))


if __name__ == "__main__":
    unittest.main()
