#!/usr/bin/env python3
"""test_tandem.py — ctest capi/python: the Python binding (tandem.py, ctypes
over libtandem.so). Every bundled scene run through Python gives the same
hash chain as `tandem run` (the C++ command line), and the Pythonic layer
(World, Body, step, hash, snapshot, restore, errors) works.

Environment: TANDEM_LIBRARY (libtandem.so), TANDEM_CLI (the tandem
executable), TANDEM_SCENES (the scenes/ directory)."""
import json
import os
import pathlib
import subprocess
import sys
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import tandem  # noqa: E402

SCENES = pathlib.Path(os.environ.get("TANDEM_SCENES", pathlib.Path(__file__).resolve().parents[2] / "scenes"))
CLI = os.environ.get("TANDEM_CLI", "tandem")
MAX_TICKS = 1200


class BundledScenes(unittest.TestCase):
    def test_every_scene_matches_tandem_run(self):
        paths = sorted(SCENES.glob("*.json"))
        self.assertGreaterEqual(len(paths), 8)
        for path in paths:
            with self.subTest(scene=path.name):
                # At most MAX_TICKS of each scene (tumbler_soak.json asks for an hour).
                scene = tandem.Scene(path)
                ticks = min(scene.ticks, MAX_TICKS)
                out = subprocess.run([CLI, "run", str(path), "--json", "--hash-every", "60", "--ticks", str(ticks)],
                                     check=True, capture_output=True, text=True).stdout
                report = json.loads(out)
                expected = [(m["tick"], int(m["hash"], 16)) for m in report["hashes"]]
                expected.append((report["final_tick"], int(report["final_hash"], 16)))
                got = scene.run(ticks=ticks, hash_every=60)
                scene.close()
                self.assertEqual(len(got), len(expected))
                for (t1, h1), (t2, h2) in zip(got, expected):
                    self.assertEqual(t1, t2)
                    self.assertEqual(h1, h2, f"{path.name}: tick {t1}: python {h1:#018x}, tandem run {h2:#018x}")
                print(f"{path.name}: {len(got)} hashes equal, final {got[-1][1]:#018x}")


class PythonicLayer(unittest.TestCase):
    def make_world(self):
        world = tandem.World()
        ground = world.create_body(position=(0, -1))
        ground.add_box(20, 1)
        box = world.create_body(type=tandem.DYNAMIC, position=(0, 2), angle="0.1")
        box.add_box("0.5", "0.5", friction=tandem.q("0.3"))
        ball = world.create_body(type=tandem.DYNAMIC, position=(-3, 1), velocity=(4, 0))
        ball.add_circle("0.25")
        return world, box, ball

    def test_step_hash_snapshot_restore(self):
        dt = tandem.q(tandem.Fraction(1, 60))
        world, box, ball = self.make_world()
        start = world.snapshot()
        chain = []
        for _ in range(90):
            world.step(dt)
            chain.append(world.state_hash())
        self.assertNotEqual(chain[0], chain[-1])
        world.restore(start)
        for expected in chain:
            world.step(dt)
            self.assertEqual(world.state_hash(), expected)
        copy = tandem.World.from_snapshot(world.snapshot())
        self.assertEqual(copy.state_hash(), world.state_hash())
        # The same world built twice gives the same chain.
        again, _, _ = self.make_world()
        for expected in chain:
            again.step(dt)
            self.assertEqual(again.state_hash(), expected)
        self.assertEqual(len(world.bodies()), 3)
        self.assertNotEqual(box.state_hash(), 0)
        ball.apply_impulse((0, 1))
        ball.velocity = (1, 2)
        self.assertEqual(ball.velocity, (tandem.q(1), tandem.q(2)))
        world.gravity = (0, "-9.81")
        self.assertEqual(world.gravity[1], tandem.q("-9.81"))
        self.assertLess(tandem.to_float(ball.position[0]), 0)
        for w in (world, copy, again):
            w.close()

    def test_numbers_are_exact(self):
        self.assertEqual(tandem.q(3), 3 << 32)
        self.assertEqual(tandem.q("1.5"), 3 << 31)
        self.assertEqual(tandem.to_text(tandem.q("-1.5")), "-1.5")
        self.assertEqual(tandem.q(tandem.Fraction(1, 2)), 1 << 31)
        with self.assertRaises(TypeError):
            tandem.q(0.1)
        with self.assertRaises(tandem.TandemError) as err:
            tandem.q("1.2x")
        self.assertIn("1.2x", str(err.exception))

    def test_errors_name_the_culprit(self):
        world, box, _ = self.make_world()
        box.destroy()
        self.assertFalse(box.valid)
        with self.assertRaises(tandem.TandemError) as err:
            box.velocity = (1, 0)
        self.assertIn("body", str(err.exception))
        self.assertEqual(err.exception.name, "invalid handle")
        with self.assertRaises(tandem.TandemError):
            world.restore(b"not a snapshot")
        with self.assertRaises(tandem.TandemError):
            world.step(tandem.q(5))
        with self.assertRaises(tandem.TandemError):
            tandem.Scene(text='{"bodies": 3}', name="bad.json")
        world.close()
        world.close()  # idempotent


class ReadmeExample(unittest.TestCase):
    def test_readme_python_block_runs(self):
        """The Python block of the README's "From other languages" section runs as written."""
        root = pathlib.Path(__file__).resolve().parents[2]
        readme = (root / "README.md").read_text(encoding="utf-8")
        section = readme[readme.index("## From other languages"):]
        block = section[section.index("```python\n") + 10:]
        block = block[:block.index("```")]
        cwd = os.getcwd()
        os.chdir(root)
        try:
            exec(compile(block, "README.md (From other languages)", "exec"), {"__name__": "readme"})
        finally:
            os.chdir(cwd)


if __name__ == "__main__":
    unittest.main()
