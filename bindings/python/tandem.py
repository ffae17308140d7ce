"""tandem.py — Tandem from Python: ctypes over libtandem.so (the C API,
capi/include/tandem_c.h), plus a thin Pythonic layer: World, Body, Scene,
step, state hash, snapshot and restore, joints (Joint: revolute, distance,
rope, weld, prismatic, wheel, motor, mouse), the per-stage profile, and the
lockstep/rollback session (tandem_session.py: Session, over a transport
given as a Python function).

Numbers: every physical quantity is a raw Q32.32 integer at the C boundary.
Here `q("0.1")`, `q(3)` or `q(Fraction(1, 60))` make one exactly (text goes
through the engine's exact decimal parser, never through float), and
`to_text(raw)` / `to_float(raw)` turn one back (float: display only). Floats
are refused as inputs: 0.1 as a binary float is not the 0.1 every peer means.

Errors: a failing call raises TandemError(code, message) with the library's
message naming the function and the culprit.

The library is found through $TANDEM_LIBRARY, else "libtandem.so" on the
loader's path (LD_LIBRARY_PATH, the install prefix's lib directory).

    import tandem
    world = tandem.World()
    ground = world.create_body(position=(0, -1))
    ground.add_box(20, 1)
    ball = world.create_body(type=tandem.DYNAMIC, position=(0, 4))
    ball.add_circle("0.5")
    for _ in range(60):
        world.step(tandem.q(tandem.Fraction(1, 60)))
    print(hex(world.state_hash()), tandem.to_text(ball.position[1]))
"""
import ctypes
import os
from ctypes import POINTER, Structure, byref, c_bool, c_char_p, c_double, c_int32, c_int64, c_size_t, c_uint8
from ctypes import c_uint16, c_uint32, c_uint64, c_void_p
from fractions import Fraction

__all__ = ["TandemError", "World", "Body", "Joint", "Scene", "command", "q", "to_text", "to_float",
           "Fraction", "STATIC", "KINEMATIC", "DYNAMIC", "LOCKSTEP", "ROLLBACK", "lib"]

STATIC, KINEMATIC, DYNAMIC = 0, 1, 2
LOCKSTEP, ROLLBACK = 0, 1
JOINT_KINDS = ["revolute", "distance", "weld", "prismatic", "mouse", "wheel", "motor"]  # TANDEM_JOINT_* order
STEPPED, STALLED, STOPPED = 0, 1, 2

# --- C structs (tandem_c.h) --------------------------------------------------------
q32 = c_int64


class Vec2(Structure):
    _fields_ = [("x", q32), ("y", q32)]


class Rot(Structure):
    _fields_ = [("c", q32), ("s", q32)]


class Transform(Structure):
    _fields_ = [("p", Vec2), ("q", Rot)]


class AABB(Structure):
    _fields_ = [("lower", Vec2), ("upper", Vec2)]


class WorldId(Structure):
    _fields_ = [("index1", c_uint16), ("generation", c_uint16)]


class BodyId(Structure):
    _fields_ = [("index1", c_uint32), ("generation", c_uint32), ("world", WorldId)]


class ShapeId(Structure):
    _fields_ = [("index1", c_uint32), ("generation", c_uint32), ("world", WorldId)]


class ObjectId(Structure):  # tandem_scene_id, tandem_replay_id, tandem_recorder_id
    _fields_ = [("index1", c_uint32), ("generation", c_uint32)]


class WorldDef(Structure):
    _fields_ = [("gravity", Vec2), ("sub_step_count", c_int32), ("contact_hertz", q32),
                ("contact_damping_ratio", q32), ("max_contact_push_speed", q32), ("joint_hertz", q32),
                ("joint_damping_ratio", q32), ("restitution_threshold", q32), ("hit_event_threshold", q32),
                ("max_linear_speed", q32), ("bounds", AABB), ("enable_sleep", c_bool),
                ("enable_continuous", c_bool), ("broad_phase", c_int32), ("user_data", c_uint64),
                ("worker_count", c_int32), ("enqueue_task", c_void_p), ("finish_task", c_void_p),
                ("user_task_context", c_void_p), ("internal_cookie", c_int32)]


class BodyDef(Structure):
    _fields_ = [("type", c_int32), ("position", Vec2), ("rotation", Rot), ("linear_velocity", Vec2),
                ("angular_velocity", q32), ("linear_damping", q32), ("angular_damping", q32),
                ("gravity_scale", q32), ("user_data", c_uint64), ("enable_sleep", c_bool), ("is_awake", c_bool),
                ("fixed_rotation", c_bool), ("is_bullet", c_bool), ("is_enabled", c_bool),
                ("internal_cookie", c_int32)]


class Filter(Structure):
    _fields_ = [("category_bits", c_uint64), ("mask_bits", c_uint64), ("group_index", c_int32)]


class ShapeDef(Structure):
    _fields_ = [("friction", q32), ("restitution", q32), ("density", q32), ("filter", Filter),
                ("user_data", c_uint64), ("is_sensor", c_bool), ("enable_hit_events", c_bool),
                ("internal_cookie", c_int32)]


class Circle(Structure):
    _fields_ = [("center", Vec2), ("radius", q32)]


class Polygon(Structure):
    _fields_ = [("vertices", Vec2 * 8), ("normals", Vec2 * 8), ("centroid", Vec2), ("radius", q32),
                ("count", c_int32)]


class JointId(Structure):
    _fields_ = [("index1", c_uint32), ("generation", c_uint32), ("world", WorldId)]


class JointBaseDef(Structure):
    _fields_ = [("body_a", BodyId), ("body_b", BodyId), ("local_anchor_a", Vec2), ("local_anchor_b", Vec2),
                ("collide_connected", c_bool), ("break_force", q32), ("break_torque", q32), ("user_data", c_uint64)]


def _joint_def(name, fields):
    return type(name, (Structure,), {"_fields_": [("base", JointBaseDef)] + fields + [("internal_cookie", c_int32)]})


RevoluteJointDef = _joint_def("RevoluteJointDef", [
    ("reference_angle", q32), ("enable_limit", c_bool), ("lower_angle", q32), ("upper_angle", q32),
    ("enable_motor", c_bool), ("motor_speed", q32), ("max_motor_torque", q32), ("enable_spring", c_bool),
    ("hertz", q32), ("damping_ratio", q32)])
DistanceJointDef = _joint_def("DistanceJointDef", [
    ("length", q32), ("enable_spring", c_bool), ("hertz", q32), ("damping_ratio", q32), ("enable_limit", c_bool),
    ("min_length", q32), ("max_length", q32), ("enable_motor", c_bool), ("motor_speed", q32),
    ("max_motor_force", q32)])
WeldJointDef = _joint_def("WeldJointDef", [
    ("reference_angle", q32), ("linear_hertz", q32), ("linear_damping_ratio", q32), ("angular_hertz", q32),
    ("angular_damping_ratio", q32)])
PrismaticJointDef = _joint_def("PrismaticJointDef", [
    ("local_axis_a", Vec2), ("reference_angle", q32), ("enable_limit", c_bool), ("lower_translation", q32),
    ("upper_translation", q32), ("enable_motor", c_bool), ("motor_speed", q32), ("max_motor_force", q32),
    ("enable_spring", c_bool), ("hertz", q32), ("damping_ratio", q32)])
MouseJointDef = _joint_def("MouseJointDef", [
    ("target", Vec2), ("hertz", q32), ("damping_ratio", q32), ("max_force", q32)])
WheelJointDef = _joint_def("WheelJointDef", [
    ("local_axis_a", Vec2), ("enable_spring", c_bool), ("hertz", q32), ("damping_ratio", q32),
    ("enable_limit", c_bool), ("lower_translation", q32), ("upper_translation", q32), ("enable_motor", c_bool),
    ("motor_speed", q32), ("max_motor_torque", q32)])
MotorJointDef = _joint_def("MotorJointDef", [
    ("linear_offset", Vec2), ("angular_offset", q32), ("max_force", q32), ("max_torque", q32),
    ("correction_factor", q32)])


class JointEvent(Structure):
    _fields_ = [("joint", JointId), ("body_a", BodyId), ("body_b", BodyId), ("kind", c_int32), ("force", Vec2),
                ("torque", q32), ("user_data", c_uint64)]


_PROFILE_STAGES = ["broad_phase_ns", "narrow_phase_ns", "islands_ns", "events_ns", "prepare_ns",
                   "integrate_velocities_ns", "warm_start_ns", "solve_ns", "integrate_positions_ns", "relax_ns",
                   "restitution_ns", "store_impulses_ns", "continuous_ns", "finalize_ns", "total_ns"]


class WorldProfile(Structure):
    _fields_ = [(name, c_int64) for name in _PROFILE_STAGES]


class JointSpec(Structure):
    _fields_ = [("type", c_int32), ("body_a_index", c_uint32), ("body_a_generation", c_uint32),
                ("body_b_index", c_uint32), ("body_b_generation", c_uint32), ("local_anchor_a", Vec2),
                ("local_anchor_b", Vec2), ("collide_connected", c_bool), ("break_force", q32),
                ("break_torque", q32), ("user_data", c_uint64), ("local_axis", Vec2), ("reference_angle", q32),
                ("enable_spring", c_bool), ("enable_limit", c_bool), ("enable_motor", c_bool), ("hertz", q32),
                ("damping_ratio", q32), ("angular_hertz", q32), ("angular_damping_ratio", q32), ("length", q32),
                ("lower", q32), ("upper", q32), ("motor_speed", q32), ("motor_force", q32), ("target", Vec2),
                ("angular_offset", q32), ("max_force", q32), ("max_torque", q32), ("correction_factor", q32)]


class Command(Structure):  # tandem_command (shapes of create_body: not wrapped here)
    _fields_ = [("type", c_int32), ("body_index", c_uint32), ("body_generation", c_uint32), ("body_def", BodyDef),
                ("shapes", c_void_p), ("shape_count", c_int32), ("vector", Vec2), ("point", Vec2),
                ("at_center", c_bool), ("scalar", q32), ("rotation", Rot), ("flag", c_bool),
                ("joint_index", c_uint32), ("joint_generation", c_uint32), ("joint_spec", JointSpec),
                ("scalar2", q32)]


class SceneInfo(Structure):
    _fields_ = [("step_hz", c_int32), ("time_step", q32), ("ticks", c_int64), ("body_count", c_int32),
                ("input_count", c_int32)]


# --- the library ---------------------------------------------------------------------
lib = ctypes.CDLL(os.environ.get("TANDEM_LIBRARY", "libtandem.so"))

_status = c_int32


def _fn(name, restype, *argtypes):
    f = getattr(lib, name)
    f.restype = restype
    f.argtypes = list(argtypes)
    return f


_fn("tandem_last_error_message", c_char_p)
_fn("tandem_status_name", c_char_p, _status)
_fn("tandem_version_string", c_char_p)
_fn("tandem_q32_from_int", q32, c_int32)
_fn("tandem_q32_from_text", _status, c_char_p, POINTER(q32))
_fn("tandem_q32_to_text", _status, q32, c_char_p, c_size_t, POINTER(c_size_t))
_fn("tandem_q32_to_double", c_double, q32)
_fn("tandem_q32_from_ratio", _status, c_int64, c_int64, POINTER(q32))
_fn("tandem_rot_from_angle", Rot, q32)
_fn("tandem_default_world_def", WorldDef)
_fn("tandem_default_body_def", BodyDef)
_fn("tandem_default_shape_def", ShapeDef)
_fn("tandem_create_world", _status, POINTER(WorldDef), POINTER(WorldId))
_fn("tandem_destroy_world", _status, WorldId)
_fn("tandem_world_is_valid", c_bool, WorldId)
_fn("tandem_world_step", _status, WorldId, q32, POINTER(c_uint32))
_fn("tandem_world_state_hash", c_uint64, WorldId)
_fn("tandem_world_set_gravity", _status, WorldId, Vec2)
_fn("tandem_world_gravity", Vec2, WorldId)
_fn("tandem_world_bodies", _status, WorldId, POINTER(BodyId), c_int32, POINTER(c_int32))
_fn("tandem_world_snapshot", _status, WorldId, POINTER(c_uint8), c_size_t, POINTER(c_size_t))
_fn("tandem_world_restore", _status, WorldId, POINTER(c_uint8), c_size_t)
_fn("tandem_create_world_from_snapshot", _status, POINTER(c_uint8), c_size_t, POINTER(WorldId))
_fn("tandem_world_set_worker_count", _status, WorldId, c_int32)
_fn("tandem_world_worker_count", c_int32, WorldId)
_fn("tandem_rollback_buffer_create", _status, POINTER(c_void_p))
_fn("tandem_rollback_buffer_free", None, c_void_p)
_fn("tandem_rollback_save", _status, WorldId, c_void_p)
_fn("tandem_rollback_restore", _status, WorldId, c_void_p)
_fn("tandem_rollback_hash", c_uint64, c_void_p)
_fn("tandem_rollback_image_size", c_size_t, c_void_p)
_fn("tandem_create_body", _status, WorldId, POINTER(BodyDef), POINTER(BodyId))
_fn("tandem_destroy_body", _status, BodyId)
_fn("tandem_body_is_valid", c_bool, BodyId)
_fn("tandem_body_position", Vec2, BodyId)
_fn("tandem_body_angle", q32, BodyId)
_fn("tandem_body_linear_velocity", Vec2, BodyId)
_fn("tandem_body_set_linear_velocity", _status, BodyId, Vec2)
_fn("tandem_body_apply_linear_impulse_to_center", _status, BodyId, Vec2, c_bool)
_fn("tandem_body_state_hash", c_uint64, BodyId)
_fn("tandem_make_box", _status, q32, q32, POINTER(Polygon))
_fn("tandem_create_polygon_shape", _status, BodyId, POINTER(ShapeDef), POINTER(Polygon), POINTER(ShapeId))
_fn("tandem_create_circle_shape", _status, BodyId, POINTER(ShapeDef), POINTER(Circle), POINTER(ShapeId))
_fn("tandem_vec2_distance", q32, Vec2, Vec2)
_fn("tandem_body_local_point", Vec2, BodyId, Vec2)
_fn("tandem_world_get_profile", WorldProfile, WorldId)
for _kind, _def in [("revolute", RevoluteJointDef), ("distance", DistanceJointDef), ("weld", WeldJointDef),
                    ("prismatic", PrismaticJointDef), ("mouse", MouseJointDef), ("wheel", WheelJointDef),
                    ("motor", MotorJointDef)]:
    _fn(f"tandem_default_{_kind}_joint_def", _def)
    _fn(f"tandem_create_{_kind}_joint", _status, WorldId, POINTER(_def), POINTER(JointId))
_fn("tandem_destroy_joint", _status, JointId)
_fn("tandem_joint_is_valid", c_bool, JointId)
_fn("tandem_joint_type", c_int32, JointId)
_fn("tandem_joint_reaction_force", Vec2, JointId)
_fn("tandem_joint_reaction_torque", q32, JointId)
_fn("tandem_joint_angle", q32, JointId)
_fn("tandem_joint_translation", q32, JointId)
_fn("tandem_joint_world_anchor_b", Vec2, JointId)
for _name, _args in [("enable_motor", [c_bool]), ("set_motor_speed", [q32]), ("set_max_motor_force", [q32]),
                     ("enable_limit", [c_bool]), ("set_limits", [q32, q32]), ("enable_spring", [c_bool]),
                     ("set_spring", [q32, q32]), ("set_length", [q32]), ("set_target", [Vec2]),
                     ("set_offsets", [Vec2, q32]), ("set_break_thresholds", [q32, q32])]:
    _fn(f"tandem_joint_{_name}", _status, JointId, *_args)
_fn("tandem_world_joint_events", _status, WorldId, POINTER(JointEvent), c_int32, POINTER(c_int32))
_fn("tandem_default_command", Command, c_int32)
_fn("tandem_command_list_push", _status, c_void_p, POINTER(Command))
_fn("tandem_bytes_assign", _status, c_void_p, POINTER(c_uint8), c_size_t)
_fn("tandem_scene_load_file", _status, c_char_p, POINTER(ObjectId))
_fn("tandem_scene_load_text", _status, c_char_p, c_size_t, c_char_p, POINTER(ObjectId))
_fn("tandem_scene_destroy", _status, ObjectId)
_fn("tandem_scene_get_info", _status, ObjectId, POINTER(SceneInfo))
_fn("tandem_scene_build", _status, ObjectId, POINTER(WorldId))
_fn("tandem_scene_body", _status, ObjectId, WorldId, c_int32, POINTER(BodyId))
_fn("tandem_scene_apply_inputs", _status, ObjectId, WorldId, c_int64)


class TandemError(Exception):
    """A refused call: `code` (TANDEM_ERROR_*), `name` and the library's message."""

    def __init__(self, code):
        self.code = code
        self.name = lib.tandem_status_name(code).decode()
        super().__init__(f"{lib.tandem_last_error_message().decode('utf-8', 'replace')} [{self.name}]")


def _check(status):
    if status != 0:
        raise TandemError(status)


# --- numbers ------------------------------------------------------------------------------
def q(value):
    """A raw Q32.32 from an int, a Fraction, or decimal text ("0.1"). Exact
    (Fractions round to nearest, ties away from zero); floats are refused."""
    if isinstance(value, bool) or isinstance(value, float):
        raise TypeError("tandem.q: pass an int, a Fraction or decimal text, not a float (not exact)")
    if isinstance(value, int) and -(1 << 31) <= value < (1 << 31):
        return lib.tandem_q32_from_int(value)
    out = q32()
    if isinstance(value, Fraction):
        _check(lib.tandem_q32_from_ratio(value.numerator, value.denominator, byref(out)))
    else:
        _check(lib.tandem_q32_from_text(str(value).encode(), byref(out)))
    return out.value


def to_text(raw):
    """Exact decimal text of a raw Q32.32 value."""
    n = c_size_t()
    _check(lib.tandem_q32_to_text(raw, None, 0, byref(n)))
    buf = ctypes.create_string_buffer(n.value + 1)
    _check(lib.tandem_q32_to_text(raw, buf, n.value + 1, byref(n)))
    return buf.value.decode()


def to_float(raw):
    """The value as a float — for display only; never feed it back."""
    return lib.tandem_q32_to_double(raw)


def _vec(xy):
    """A Vec2 from a pair of numbers (as for q()); a Vec2 (raw) passes through."""
    return xy if isinstance(xy, Vec2) else Vec2(q(xy[0]), q(xy[1]))


# --- objects ------------------------------------------------------------------------------
class _Owned:
    """Something the library owns for us, named by self.id: close() (idempotent,
    also at garbage collection and at the end of a with block) calls
    _destroy(id) unless _alive(id) says it is gone already."""

    id = None

    def _alive(self, _id):
        return True

    def close(self):
        if self.id is not None and self._alive(self.id):
            _check(self._destroy(self.id))
        self.id = None

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class RollbackBuffer(_Owned):
    """A compact rollback snapshot (tandem_rollback_buffer, replay/rollback.h):
    a few hundred bytes per moving body, for netcode that saves every tick.
    Same build only (files and other machines: World.snapshot()). Freed by
    close() or at garbage collection."""

    _destroy = staticmethod(lambda handle: lib.tandem_rollback_buffer_free(handle) or 0)

    def __init__(self):
        handle = c_void_p()
        _check(lib.tandem_rollback_buffer_create(byref(handle)))
        self.id = handle

    def save(self, world):
        """Replaces the buffer's contents with the world's state."""
        _check(lib.tandem_rollback_save(world.id, self.id))

    def restore(self, world):
        """Replaces the world's state with the buffer's."""
        _check(lib.tandem_rollback_restore(world.id, self.id))

    def hash(self):
        """XXH3-64 of the compact image (0 when empty); equal states, equal hashes."""
        return lib.tandem_rollback_hash(self.id)

    def __len__(self):
        """The compact image's size in bytes."""
        return lib.tandem_rollback_image_size(self.id)


class World(_Owned):
    """A physics world (destroyed by close() or at garbage collection)."""

    _destroy = staticmethod(lambda world_id: lib.tandem_destroy_world(world_id))
    _alive = staticmethod(lambda world_id: lib.tandem_world_is_valid(world_id))

    def __init__(self, gravity=None, world_id=None, **settings):
        if world_id is None:
            d = lib.tandem_default_world_def()
            if gravity is not None:
                d.gravity = _vec(gravity)
            for key, value in settings.items():
                setattr(d, key, value)
            world_id = WorldId()
            _check(lib.tandem_create_world(byref(d), byref(world_id)))
        self.id = world_id

    def step(self, time_step):
        """Advances by time_step seconds (raw Q32.32; see q()); returns the step flags."""
        flags = c_uint32()
        _check(lib.tandem_world_step(self.id, time_step, byref(flags)))
        return flags.value

    def state_hash(self):
        """XXH3-64 of the canonical state (what `tandem run` prints)."""
        return lib.tandem_world_state_hash(self.id)

    def create_body(self, type=STATIC, position=(0, 0), angle=None, velocity=None, **fields):
        """Creates a body; numbers as for q(). Returns a Body."""
        d = lib.tandem_default_body_def()
        d.type = type
        d.position = _vec(position)
        if angle is not None:
            d.rotation = lib.tandem_rot_from_angle(q(angle))
        if velocity is not None:
            d.linear_velocity = _vec(velocity)
        for key, value in fields.items():
            setattr(d, key, value)
        body = BodyId()
        _check(lib.tandem_create_body(self.id, byref(d), byref(body)))
        return Body(body)

    @property
    def gravity(self):
        g = lib.tandem_world_gravity(self.id)
        return (g.x, g.y)

    @gravity.setter
    def gravity(self, value):
        _check(lib.tandem_world_set_gravity(self.id, _vec(value)))

    def bodies(self):
        """Live bodies in ascending index."""
        n = c_int32()
        _check(lib.tandem_world_bodies(self.id, None, 0, byref(n)))
        arr = (BodyId * n.value)()
        _check(lib.tandem_world_bodies(self.id, arr, n.value, byref(n)))
        return [Body(arr[i]) for i in range(n.value)]

    def snapshot(self):
        """The canonical state image as bytes."""
        n = c_size_t()
        _check(lib.tandem_world_snapshot(self.id, None, 0, byref(n)))
        buf = (c_uint8 * n.value)()
        _check(lib.tandem_world_snapshot(self.id, buf, n.value, byref(n)))
        return bytes(buf)

    def restore(self, image):
        """Replaces the state with an image (validated first; refused: unchanged)."""
        buf = (c_uint8 * len(image)).from_buffer_copy(image)
        _check(lib.tandem_world_restore(self.id, buf, len(image)))

    @property
    def worker_count(self):
        """Threads that run a step (World(worker_count=4) or set it between
        steps, 1…16); the results are bit-identical for every value."""
        return lib.tandem_world_worker_count(self.id)

    @worker_count.setter
    def worker_count(self, value):
        _check(lib.tandem_world_set_worker_count(self.id, value))

    def rollback_save(self, buffer=None):
        """Saves the state into a compact RollbackBuffer (a new one, or
        `buffer`, reused) and returns it; see RollbackBuffer."""
        buffer = buffer if buffer is not None else RollbackBuffer()
        buffer.save(self)
        return buffer

    def rollback_restore(self, buffer):
        """Restores a RollbackBuffer (refused: unchanged); later steps are
        bit-identical to the run it was saved from."""
        buffer.restore(self)

    def create_joint(self, kind, body_a, body_b, anchor_a=(0, 0), anchor_b=(0, 0), **fields):
        """Creates a joint of `kind` ("revolute", "distance", "weld", "prismatic",
        "mouse", "wheel", "motor") between two Bodies; anchors in each body's
        frame (m); other fields of the kind's definition by name (numbers as
        for q(), bools, vectors as pairs). Returns a Joint."""
        d = getattr(lib, f"tandem_default_{kind}_joint_def")()
        d.base.body_a, d.base.body_b = body_a.id, body_b.id
        d.base.local_anchor_a, d.base.local_anchor_b = _vec(anchor_a), _vec(anchor_b)
        for key, value in fields.items():
            target = d.base if key in ("collide_connected", "break_force", "break_torque", "user_data") else d
            old = getattr(target, key)
            if isinstance(old, Vec2):
                value = _vec(value)
            elif isinstance(old, int) and not isinstance(old, bool) and not isinstance(value, bool):
                value = q(value) if key != "user_data" else value
            setattr(target, key, value)
        joint = JointId()
        _check(getattr(lib, f"tandem_create_{kind}_joint")(self.id, byref(d), byref(joint)))
        return Joint(joint)

    def create_rope(self, body_a, body_b, length, anchor_a=(0, 0), anchor_b=(0, 0)):
        """A rope: a distance joint that only pulls, never longer than `length` m."""
        return self.create_joint("distance", body_a, body_b, anchor_a, anchor_b, length=length, enable_spring=True,
                                 enable_limit=True, min_length=0, max_length=length)

    def joint_events(self):
        """Joints gone in the last step: [(joint, kind, force, torque, user_data)]
        (kind 0 broke, 1 destroyed with a body)."""
        n = c_int32()
        _check(lib.tandem_world_joint_events(self.id, None, 0, byref(n)))
        arr = (JointEvent * n.value)()
        _check(lib.tandem_world_joint_events(self.id, arr, n.value, byref(n)))
        return [(Joint(e.joint), e.kind, (e.force.x, e.force.y), e.torque, e.user_data) for e in arr]

    def profile(self):
        """Wall-clock nanoseconds per stage of the last step (timing only): a dict."""
        p = lib.tandem_world_get_profile(self.id)
        return {name: getattr(p, name) for name in _PROFILE_STAGES}

    @classmethod
    def from_snapshot(cls, image):
        """A new world from a state image."""
        buf = (c_uint8 * len(image)).from_buffer_copy(image)
        world_id = WorldId()
        _check(lib.tandem_create_world_from_snapshot(buf, len(image), byref(world_id)))
        return cls(world_id=world_id)


class Body:
    """A body handle (a value; stale after its destruction: calls then raise)."""

    def __init__(self, body_id):
        self.id = body_id

    def add_box(self, half_width, half_height, **fields):
        """Attaches a box (half extents in m) centred on the body origin."""
        poly = Polygon()
        _check(lib.tandem_make_box(q(half_width), q(half_height), byref(poly)))
        d = lib.tandem_default_shape_def()
        for key, value in fields.items():
            setattr(d, key, value)
        shape = ShapeId()
        _check(lib.tandem_create_polygon_shape(self.id, byref(d), byref(poly), byref(shape)))
        return shape

    def add_circle(self, radius, center=(0, 0), **fields):
        """Attaches a circle (radius in m)."""
        circle = Circle(_vec(center), q(radius))
        d = lib.tandem_default_shape_def()
        for key, value in fields.items():
            setattr(d, key, value)
        shape = ShapeId()
        _check(lib.tandem_create_circle_shape(self.id, byref(d), byref(circle), byref(shape)))
        return shape

    @property
    def valid(self):
        return lib.tandem_body_is_valid(self.id)

    @property
    def position(self):
        """Origin position (raw Q32.32 x, y)."""
        p = lib.tandem_body_position(self.id)
        return (p.x, p.y)

    @property
    def angle(self):
        return lib.tandem_body_angle(self.id)

    @property
    def velocity(self):
        v = lib.tandem_body_linear_velocity(self.id)
        return (v.x, v.y)

    @velocity.setter
    def velocity(self, value):
        _check(lib.tandem_body_set_linear_velocity(self.id, _vec(value)))

    def apply_impulse(self, impulse, wake=True):
        """Applies a linear impulse (N·s) at the centre of mass."""
        _check(lib.tandem_body_apply_linear_impulse_to_center(self.id, _vec(impulse), wake))

    def state_hash(self):
        return lib.tandem_body_state_hash(self.id)

    def destroy(self):
        _check(lib.tandem_destroy_body(self.id))


class Scene(_Owned):
    """A JSON scene file (docs/scene-format.md), loaded and ready to build."""

    _destroy = staticmethod(lambda scene_id: lib.tandem_scene_destroy(scene_id))

    def __init__(self, path=None, text=None, name="scene"):
        self.id = ObjectId()
        if path is not None:
            _check(lib.tandem_scene_load_file(str(path).encode(), byref(self.id)))
        else:
            data = text.encode()
            _check(lib.tandem_scene_load_text(data, len(data), name.encode(), byref(self.id)))
        info = SceneInfo()
        _check(lib.tandem_scene_get_info(self.id, byref(info)))
        self.step_hz, self.time_step, self.ticks = info.step_hz, info.time_step, info.ticks
        self.body_count, self.input_count = info.body_count, info.input_count

    def build(self):
        """A new World built from the scene."""
        world_id = WorldId()
        _check(lib.tandem_scene_build(self.id, byref(world_id)))
        return World(world_id=world_id)

    def body(self, world, index):
        """Scene body `index` in a world built from this scene."""
        body = BodyId()
        _check(lib.tandem_scene_body(self.id, world.id, index, byref(body)))
        return Body(body)

    def step(self, world, tick):
        """Applies the scripted inputs for `tick`, then steps once (tick → tick + 1)."""
        _check(lib.tandem_scene_apply_inputs(self.id, world.id, tick))
        return world.step(self.time_step)

    def run(self, ticks=None, hash_every=60):
        """Builds and runs the scene like `tandem run`: [(tick, hash)] at tick 0,
        every hash_every ticks and at the end."""
        ticks = self.ticks if ticks is None else ticks
        with self.build() as world:
            marks = [(0, world.state_hash())]
            for tick in range(ticks):
                self.step(world, tick)
                if hash_every and (tick + 1) % hash_every == 0 and tick + 1 != ticks:
                    marks.append((tick + 1, world.state_hash()))
            marks.append((ticks, world.state_hash()))
            return marks


class Joint:
    """A joint handle (a value; stale once destroyed or broken: calls then raise)."""

    def __init__(self, joint_id):
        self.id = joint_id

    @property
    def valid(self):
        return lib.tandem_joint_is_valid(self.id)

    @property
    def kind(self):
        return JOINT_KINDS[lib.tandem_joint_type(self.id)]

    @property
    def reaction_force(self):
        """Force on body B in the last sub-step, N (raw x, y)."""
        f = lib.tandem_joint_reaction_force(self.id)
        return (f.x, f.y)

    @property
    def reaction_torque(self):
        return lib.tandem_joint_reaction_torque(self.id)

    @property
    def angle(self):
        return lib.tandem_joint_angle(self.id)

    @property
    def translation(self):
        """Prismatic/wheel translation or the distance joint's current length, m (raw)."""
        return lib.tandem_joint_translation(self.id)

    def set_motor(self, speed, max_force, enable=True):
        """Motor speed (rad/s or m/s) and max torque/force (N·m or N)."""
        _check(lib.tandem_joint_enable_motor(self.id, enable))
        _check(lib.tandem_joint_set_motor_speed(self.id, q(speed)))
        _check(lib.tandem_joint_set_max_motor_force(self.id, q(max_force)))

    def set_limits(self, lower, upper, enable=True):
        _check(lib.tandem_joint_enable_limit(self.id, enable))
        _check(lib.tandem_joint_set_limits(self.id, q(lower), q(upper)))

    def set_spring(self, hertz, damping_ratio, enable=True):
        _check(lib.tandem_joint_enable_spring(self.id, enable))
        _check(lib.tandem_joint_set_spring(self.id, q(hertz), q(damping_ratio)))

    def set_length(self, length):
        _check(lib.tandem_joint_set_length(self.id, q(length)))

    def set_target(self, target):
        _check(lib.tandem_joint_set_target(self.id, _vec(target)))

    def set_offsets(self, linear, angular):
        _check(lib.tandem_joint_set_offsets(self.id, _vec(linear), q(angular)))

    def set_break_thresholds(self, force, torque):
        _check(lib.tandem_joint_set_break_thresholds(self.id, q(force), q(torque)))

    def destroy(self):
        _check(lib.tandem_destroy_joint(self.id))


def command(type, **fields):
    """An engine command (tandem_command, TANDEM_COMMAND_* type) with fields set by name."""
    c = lib.tandem_default_command(type)
    for key, value in fields.items():
        setattr(c, key, value)
    return c

