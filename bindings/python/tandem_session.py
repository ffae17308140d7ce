"""tandem_session.py — the lockstep / rollback session (replay/session.h)
from Python, over the C API (capi/include/tandem_c_session.h): a Session per
peer, the transport and the game given as Python functions. Import tandem
first (it loads the library).

    import tandem
    from tandem_session import Session
    session = Session(world, send=lambda endpoint, packet: ..., make_commands=..., local_endpoint=0)
    session.receive(from_endpoint, packet)     # whatever the transport delivered
    session.advance(my_input_bytes)            # once per frame
"""
import ctypes
from ctypes import CFUNCTYPE, POINTER, Structure, byref, c_bool, c_char_p, c_int32, c_size_t, c_uint8, c_uint32
from ctypes import c_int64, c_uint64, c_void_p

from tandem import ObjectId, WorldId, _check, _fn, _Owned, _status, lib, q32

__all__ = ["Session"]

class SessionConfig(Structure):
    _fields_ = [("mode", c_int32), ("player_count", c_uint32), ("spectator_count", c_uint32),
                ("local_endpoint", c_uint32), ("input_bytes", c_uint32), ("input_delay", c_uint32),
                ("prediction_window", c_uint32), ("session_id", c_uint64), ("time_step", q32),
                ("history_ticks", c_uint32), ("disconnect_timeout_frames", c_uint32), ("record_replay", c_bool),
                ("keyframe_interval", c_uint32)]


_SEND_FN = CFUNCTYPE(None, c_void_p, c_uint32, POINTER(c_uint8), c_size_t)
_MAKE_COMMANDS_FN = CFUNCTYPE(c_int32, c_void_p, c_int64, POINTER(c_uint8), c_uint32, c_uint32, WorldId, c_void_p)
_AFTER_STEP_FN = CFUNCTYPE(None, c_void_p, c_int64, WorldId)
_SAVE_GAME_FN = CFUNCTYPE(None, c_void_p, c_void_p)
_LOAD_GAME_FN = CFUNCTYPE(None, c_void_p, POINTER(c_uint8), c_size_t)


class SessionCallbacks(Structure):
    _fields_ = [("context", c_void_p), ("send", _SEND_FN), ("make_commands", _MAKE_COMMANDS_FN),
                ("after_step", _AFTER_STEP_FN), ("save_game", _SAVE_GAME_FN), ("load_game", _LOAD_GAME_FN)]


class SessionStop(Structure):
    _fields_ = [("state", c_int32), ("tick", c_int64), ("endpoint", c_uint32), ("local_hash", c_uint64),
                ("remote_hash", c_uint64), ("last_heard_tick", c_int64)]


_STAT_NAMES = ["frames", "stalls", "rollbacks", "max_rollback_depth", "resimulated_ticks", "ticks_simulated",
               "packets_sent", "bytes_sent", "packets_received", "bytes_received", "packets_rejected",
               "packets_stale", "commands_refused", "hashes_compared", "hashes_skipped"]


class SessionStats(Structure):
    _fields_ = [(name, c_uint64) for name in _STAT_NAMES]


_fn("tandem_default_session_config", SessionConfig)
_fn("tandem_session_create", _status, WorldId, POINTER(SessionConfig), POINTER(SessionCallbacks),
    POINTER(ObjectId))
_fn("tandem_session_destroy", _status, ObjectId)
_fn("tandem_session_advance_frame", _status, ObjectId, POINTER(c_uint8), c_size_t, POINTER(c_int32))
_fn("tandem_session_idle_frame", _status, ObjectId, POINTER(c_int32))
_fn("tandem_session_receive", _status, ObjectId, c_uint32, POINTER(c_uint8), c_size_t)
_fn("tandem_session_current_tick", c_int64, ObjectId)
_fn("tandem_session_confirmed_tick", c_int64, ObjectId)
_fn("tandem_session_confirmed_hash", c_uint64, ObjectId, c_int64)
_fn("tandem_session_frames_ahead", c_int32, ObjectId)
_fn("tandem_session_state", c_int32, ObjectId)
_fn("tandem_session_state_name", c_char_p, c_int32)
_fn("tandem_session_get_stop", _status, ObjectId, POINTER(SessionStop))
_fn("tandem_session_get_stats", _status, ObjectId, POINTER(SessionStats))
_fn("tandem_session_replay_bytes", _status, ObjectId, POINTER(c_uint8), c_size_t, POINTER(c_size_t))


class Session(_Owned):
    """A lockstep or rollback session (replay/session.h) for one peer.

    send(endpoint, packet_bytes) is the transport; make_commands(tick, inputs,
    world_id) returns the tick's engine commands (a list of command(...)) from
    the list of every player's input bytes; after_step(tick), save_game() ->
    bytes and load_game(bytes) are optional. Config fields by name (defaults:
    the C++ ones). Exceptions raised in a callback stop the session."""

    _destroy = staticmethod(lambda session_id: lib.tandem_session_destroy(session_id))

    def __init__(self, world, send, make_commands, after_step=None, save_game=None, load_game=None, **config):
        c = lib.tandem_default_session_config()
        for key, value in config.items():
            setattr(c, key, value)
        self.input_bytes = c.input_bytes

        def send_cb(_ctx, endpoint, data, size):
            send(endpoint, ctypes.string_at(data, size))

        def make_cb(_ctx, tick, data, players, input_bytes, world_id, out):
            try:
                raw = ctypes.string_at(data, players * input_bytes)
                inputs = [raw[p * input_bytes:(p + 1) * input_bytes] for p in range(players)]
                for cmd in make_commands(tick, inputs, world_id):
                    status = lib.tandem_command_list_push(out, byref(cmd))
                    if status != 0:
                        return status
                return 0
            except Exception:  # noqa: BLE001 — a callback must not raise through C
                return 14  # TANDEM_ERROR_INTERNAL: the session stops (state error)

        def save_cb(_ctx, out):
            data = save_game()
            buf = (c_uint8 * len(data)).from_buffer_copy(data)
            lib.tandem_bytes_assign(out, buf, len(data))

        cb = SessionCallbacks()
        self._callbacks = [_SEND_FN(send_cb), _MAKE_COMMANDS_FN(make_cb)]  # kept alive with the session
        cb.send, cb.make_commands = self._callbacks
        if after_step is not None:
            self._callbacks.append(_AFTER_STEP_FN(lambda _ctx, tick, _w: after_step(tick)))
            cb.after_step = self._callbacks[-1]
        if save_game is not None:
            self._callbacks.append(_SAVE_GAME_FN(save_cb))
            cb.save_game = self._callbacks[-1]
        if load_game is not None:
            self._callbacks.append(_LOAD_GAME_FN(lambda _ctx, data, size: load_game(ctypes.string_at(data, size))))
            cb.load_game = self._callbacks[-1]
        self.id = ObjectId()
        _check(lib.tandem_session_create(world.id, byref(c), byref(cb), byref(self.id)))


    def advance(self, local_input):
        """One frame with this peer's input (input_bytes bytes): STEPPED, STALLED or STOPPED."""
        buf = (c_uint8 * len(local_input)).from_buffer_copy(bytes(local_input))
        result = c_int32()
        _check(lib.tandem_session_advance_frame(self.id, buf, len(local_input), byref(result)))
        return result.value

    def idle(self):
        result = c_int32()
        _check(lib.tandem_session_idle_frame(self.id, byref(result)))
        return result.value

    def receive(self, from_endpoint, packet):
        buf = (c_uint8 * len(packet)).from_buffer_copy(packet)
        _check(lib.tandem_session_receive(self.id, from_endpoint, buf, len(packet)))

    @property
    def current_tick(self):
        return lib.tandem_session_current_tick(self.id)

    @property
    def confirmed_tick(self):
        return lib.tandem_session_confirmed_tick(self.id)

    def confirmed_hash(self, tick):
        return lib.tandem_session_confirmed_hash(self.id, tick)

    @property
    def frames_ahead(self):
        return lib.tandem_session_frames_ahead(self.id)

    @property
    def state(self):
        """"running", "desynced", "peer left", ..."""
        return lib.tandem_session_state_name(lib.tandem_session_state(self.id)).decode()

    def stop_info(self):
        s = SessionStop()
        _check(lib.tandem_session_get_stop(self.id, byref(s)))
        return {name: getattr(s, name) for name, _ in SessionStop._fields_}

    def stats(self):
        s = SessionStats()
        _check(lib.tandem_session_get_stats(self.id, byref(s)))
        return {name: getattr(s, name) for name in _STAT_NAMES}

    def replay_bytes(self):
        n = c_size_t()
        _check(lib.tandem_session_replay_bytes(self.id, None, 0, byref(n)))
        buf = (c_uint8 * n.value)()
        _check(lib.tandem_session_replay_bytes(self.id, buf, n.value, byref(n)))
        return bytes(buf)
