#!/usr/bin/env python3
"""test_tandem.py — ctest capi/python: the Python binding (tandem.py, ctypes
over libtandem.so). Every bundled scene run through Python gives the same
hash chain as `tandem run` (the C++ command line), and the Pythonic layer
(World, Body, step, hash, snapshot, restore, errors) works; joints (revolute
motor, distance, rope, mouse, reactions, breaks, the README grappling hook =
the C++ reference's hashes), the profile, and two sessions over an
in-process loopback.

Environment: TANDEM_LIBRARY (libtandem.so), TANDEM_CLI (the tandem
executable), TANDEM_SCENES (the scenes/ directory), TANDEM_ROPE_NATIVE (the
C++ grappling hook, capi/tests/rope_native.cpp; its test is skipped without it)."""
import ctypes
import json
import os
import pathlib
import subprocess
import sys
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import tandem  # noqa: E402
from tandem_session import Session  # noqa: E402

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

    def test_workers_and_rollback_buffer(self):
        dt = tandem.q(tandem.Fraction(1, 60))
        plain, _, _ = self.make_world()
        chain = []
        for _ in range(60):
            plain.step(dt)
            chain.append(plain.state_hash())
        world = tandem.World(worker_count=2)
        self.assertEqual(world.worker_count, 2)
        world.close()
        # Two workers, then three from tick 20 on; a rollback at tick 30.
        world, _, _ = self.make_world()
        world.worker_count = 2
        with self.assertRaises(tandem.TandemError) as bad:
            world.worker_count = 17
        self.assertIn("worker_count 17 is outside [1, 16]", str(bad.exception))
        self.assertEqual(world.worker_count, 2)
        saved = None
        for tick in range(40):
            if tick == 20:
                world.worker_count = 3
            if tick == 30:
                saved = world.rollback_save()
            world.step(dt)
            self.assertEqual(world.state_hash(), chain[tick])
        self.assertGreater(len(saved), 0)
        self.assertNotEqual(saved.hash(), 0)
        world.rollback_restore(saved)
        self.assertEqual(world.rollback_save().hash(), saved.hash())
        for tick in range(30, 60):
            world.step(dt)
            self.assertEqual(world.state_hash(), chain[tick])
        saved.close()
        for w in (plain, world):
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


class Joints(unittest.TestCase):
    DT = tandem.q(tandem.Fraction(1, 60))

    def test_revolute_motor_distance_mouse_rope_and_profile(self):
        world = tandem.World()
        ground = world.create_body(position=(0, 0))
        wheel = world.create_body(type=tandem.DYNAMIC, position=(0, 5))
        wheel.add_circle("0.5")
        pin = world.create_joint("revolute", ground, wheel, anchor_a=(0, 5))
        self.assertEqual(pin.kind, "revolute")
        pin.set_motor(speed=3, max_force=100)             # rad/s, N·m
        bob = world.create_body(type=tandem.DYNAMIC, position=(3, 5))
        bob.add_circle("0.25")
        rope = world.create_rope(ground, bob, length=3, anchor_a=(3, 8))
        weight = world.create_body(type=tandem.DYNAMIC, position=(-3, 5))
        weight.add_box("0.3", "0.3")
        spring = world.create_joint("distance", ground, weight, anchor_a=(-3, 8), length=2, enable_spring=True,
                                    hertz=2, damping_ratio="0.1")
        dragged = world.create_body(type=tandem.DYNAMIC, position=(6, 2))
        dragged.add_box("0.5", "0.5")
        mouse = world.create_joint("mouse", ground, dragged, target=(6, 2), max_force=500)
        mouse.set_target((8, 4))
        for _ in range(120):
            world.step(self.DT)
        self.assertNotEqual(pin.reaction_force, (0, 0))   # holds the wheel up against gravity
        self.assertGreater(pin.reaction_force[1], 0)
        self.assertLessEqual(rope.translation, tandem.q("3.001"))  # a rope never gets longer
        self.assertGreater(tandem.to_float(spring.translation), 2)  # the spring stretches under the weight
        self.assertLess(abs(tandem.to_float(dragged.position[0]) - 8), 0.1)  # pulled to the target
        profile = world.profile()
        self.assertGreater(profile["total_ns"], 0)
        self.assertLessEqual(sum(v for k, v in profile.items() if k != "total_ns"), profile["total_ns"])
        # A break threshold below the rope's tension breaks it, once.
        rope.set_break_thresholds("0.001", 0)
        world.step(self.DT)
        events = world.joint_events()
        self.assertEqual(len(events), 1)
        self.assertEqual(events[0][1], 0)
        self.assertFalse(rope.valid)
        with self.assertRaises(tandem.TandemError) as err:
            rope.set_length(2)
        self.assertEqual(err.exception.name, "invalid handle")
        with self.assertRaises(tandem.TandemError) as err:
            world.create_joint("revolute", wheel, wheel)
        self.assertIn("body", str(err.exception))
        with self.assertRaises(tandem.TandemError):
            pin.set_target((1, 1))                          # not a mouse joint
        world.close()

    @unittest.skipUnless(os.environ.get("TANDEM_ROPE_NATIVE"), "TANDEM_ROPE_NATIVE not set")
    def test_grappling_hook_matches_the_cpp_reference(self):
        """The README's grappling hook in Python prints rope_native.cpp's hashes."""
        native = subprocess.run([os.environ["TANDEM_ROPE_NATIVE"]], check=True, capture_output=True, text=True)
        world = tandem.World()
        ceiling = world.create_body(position=(0, 10))
        player = world.create_body(type=tandem.DYNAMIC, position=(-4, 3))
        player.add_circle("0.4")
        hook, rope, lines = None, 0, []
        one, twenty, step = tandem.q(1), tandem.q(20), tandem.q(tandem.Fraction(-5, 100))
        aim = tandem.Vec2(0, tandem.q(10))
        for tick in range(420):
            if tick == 5 and hook is None:
                rope = max(tandem.lib.tandem_vec2_distance(aim, tandem.lib.tandem_body_position(player.id)), one)
                local = tandem.lib.tandem_body_local_point(ceiling.id, aim)
                d = tandem.lib.tandem_default_distance_joint_def()
                d.base.body_a, d.base.body_b, d.base.local_anchor_a = ceiling.id, player.id, local
                d.length, d.enable_spring, d.enable_limit, d.max_length = rope, True, True, rope
                joint = tandem.JointId()
                tandem._check(tandem.lib.tandem_create_distance_joint(world.id, ctypes.byref(d), ctypes.byref(joint)))
                hook = tandem.Joint(joint)
            if hook is not None and 120 <= tick < 200:
                rope = min(max(rope + step, one), twenty)
                tandem._check(tandem.lib.tandem_joint_set_limits(hook.id, 0, rope))
            if tick == 300 and hook is not None:
                hook.destroy()
                hook = None
            world.step(self.DT)
            if (tick + 1) % 60 == 0:
                lines.append(f"rope tick {tick + 1} hash 0x{world.state_hash():016x}")
        self.assertEqual(lines, native.stdout.split("\n")[:-1])
        world.close()


class Sessions(unittest.TestCase):
    def test_two_peers_over_a_loopback(self):
        """Two rollback peers, packets delivered two frames late (so remote inputs
        are predicted and rolled back), confirm the same hashes."""
        queue, worlds, sessions, bodies = [], [], [], []
        frame = [0]
        for endpoint in range(2):
            world = tandem.World()
            world.create_body(position=(0, -1)).add_box(20, 1)
            players = []
            for p in range(2):
                b = world.create_body(type=tandem.DYNAMIC, position=(3 * p - 1, 2))
                b.add_box("0.5", "0.5")
                players.append(b)

            def send(to, packet, frm=endpoint):
                queue.append((frame[0] + 2, frm, to, packet))

            def make_commands(tick, inputs, _world, players=players):
                out = []
                for p, data in enumerate(inputs):
                    if data[0]:
                        out.append(tandem.command(5, body_index=players[p].id.index1 - 1,  # APPLY_LINEAR_IMPULSE
                                                  body_generation=players[p].id.generation, at_center=True,
                                                  vector=tandem.Vec2(tandem.q(1 if data[0] == 1 else -1), 0)))
                return out

            worlds.append(world)
            bodies.append(players)
            sessions.append(Session(world, send, make_commands, mode=tandem.ROLLBACK, local_endpoint=endpoint,
                                    input_delay=0, session_id=7))
        while min(s.confirmed_tick for s in sessions) < 90 and frame[0] < 600:
            for endpoint, session in enumerate(sessions):
                due = [m for m in queue if m[2] == endpoint and m[0] <= frame[0]]
                for m in due:
                    queue.remove(m)
                    session.receive(m[1], m[3])
                self.assertIn(session.advance(bytes([(frame[0] // 5 + endpoint) % 3, 0, 0, 0])),
                              (tandem.STEPPED, tandem.STALLED))
            frame[0] += 1
        for session in sessions:
            self.assertEqual(session.state, "running")
            self.assertGreaterEqual(session.confirmed_tick, 90)
        self.assertGreater(sessions[0].stats()["rollbacks"], 0)
        for tick in range(1, 91):
            self.assertEqual(sessions[0].confirmed_hash(tick), sessions[1].confirmed_hash(tick))
        self.assertNotEqual(sessions[0].confirmed_hash(90), sessions[0].confirmed_hash(1))
        self.assertEqual(sessions[0].stop_info()["state"], 1)
        for s in sessions:
            s.close()
        for w in worlds:
            w.close()


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
