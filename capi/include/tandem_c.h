/* tandem_c.h — the C API of Tandem (C11; also valid C++). One header, one
 * shared library (libtandem.so), callable from any language with a C FFI:
 * Python (ctypes), C# (P/Invoke, as a Unity project would), Rust, Go, Lua...
 *
 * DESIGN. The C layer mirrors the C++ API (physics/tandem.h, replay/ headers, the
 * scene loader) one to one and adds no arithmetic: every function converts
 * its arguments field by field, calls the C++ function and converts the
 * result back, so a world driven through this header computes exactly the
 * same bits, tick for tick, as one driven from C++ (a test checks this).
 *
 * NUMBERS. Every physical quantity crosses the boundary as the raw Q32.32
 * integer (tandem_q32 = int64_t, value = raw / 2^32), in SI units (m, s, kg,
 * rad, N). Helpers convert raw values to and from Q16.16, exact decimal text
 * and — for display only — double; there is deliberately no conversion from
 * floating point (write "0.1", not 0.1, to get the same bits everywhere).
 *
 * HANDLES. Worlds, bodies, shapes and joints are small POD structs (index +
 * 1 and a generation, plus the world for bodies, shapes and joints); the
 * all-zero handle is null. A stale handle (its object destroyed) is
 * detected, never dereferenced. Sessions, recorders, loaded replays, decoded
 * states and loaded scenes are handles of the same kind, owned by this
 * library until tandem_*_destroy().
 *
 * CALLBACKS are plain function pointers with a `void* context` the caller
 * chooses (the session's transport and game, payload handlers, progress,
 * the custom filter). They run on the calling thread, inside the call that
 * triggers them, and must not destroy the object that calls them. The
 * exception: a world's task system (tandem_world_def.enqueue_task /
 * finish_task, used when worker_count > 1) may run the tandem_task_fn it is
 * handed on any thread, in any order, before finish_task returns.
 *
 * ERRORS. A function that can fail returns a tandem_status (TANDEM_OK = 0).
 * Every such function records the outcome as the CALLING THREAD's last error:
 * tandem_last_error_code() and tandem_last_error_message() (a UTF-8 message
 * naming the function and the culprit, e.g. "body_set_linear_velocity: body
 * {index 3, generation 2} was destroyed"; "" after a success). The message
 * stays valid until the next status-returning call on the same thread.
 * Value getters (tandem_body_position, ...) return the value directly; given
 * an invalid handle they return the documented default (zero, the identity,
 * false, a null handle) and do not touch the last error — call
 * tandem_body_check() and friends for a status. No C++ exception ever leaves
 * this library: anything thrown inside (out of memory included) becomes a
 * status.
 *
 * BUFFERS. Functions that return a list take (out, capacity, out_count):
 * *out_count (required) receives the number of elements of the full result.
 * Pass out = NULL and capacity = 0 to ask only for the size (TANDEM_OK). With
 * a non-zero capacity smaller than the result nothing is written and the
 * status is TANDEM_ERROR_BUFFER_TOO_SMALL, its message naming both sizes.
 * Memory this library allocates for a caller (report texts) is freed by the
 * matching tandem_free_*() function and by nothing else.
 *
 * THREADS. As the C++ API: worlds are independent, one world is used by one
 * thread at a time (a step may use worker_count threads inside; the bits do
 * not depend on it); the last error is per thread.
 *
 * FILES. This umbrella includes the parts, each usable alone:
 *   tandem_c_base.h     status codes, numbers, value types, handles, definitions, geometry
 *   tandem_c_world.h    worlds, bodies, shapes, queries, events, the world profile
 *   tandem_c_geometry.h single-shape validation, mass, bounds, point tests, ray casts, manifolds,
 *                       GJK distance, shape casts, time of impact
 *   tandem_c_joint.h    joints (physics/joint.h)
 *   tandem_c_replay.h   snapshots, hashes, commands, recorders, replays, verify, diff, sync test, scenes
 *   tandem_c_session.h  the lockstep / rollback session (replay/session.h)
 */
#ifndef TANDEM_C_H
#define TANDEM_C_H

#include "tandem_c_base.h"
#include "tandem_c_world.h"
#include "tandem_c_geometry.h"
#include "tandem_c_joint.h"
#include "tandem_c_replay.h"
#include "tandem_c_session.h"

#endif /* TANDEM_C_H */
