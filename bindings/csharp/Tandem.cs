// Tandem.cs — Tandem from C#: P/Invoke declarations over libtandem.so /
// tandem.dll (the C API, capi/include/tandem_c.h) and a thin layer (World,
// Body, Scene, Q). Drop this file and the native library into a Unity
// project's Plugins folder; [DllImport("tandem")] finds libtandem.so on
// Linux, tandem.dll on Windows and libtandem.dylib on macOS.
//
// Numbers cross as raw Q32.32 longs. Q.FromInt / Q.FromText / Q.Ratio make
// them exactly; Q.ToText gives exact decimal text and Q.ToDouble a double for
// display only (never feed a double back: peers would disagree).
//
// Structs mirror the C structs field for field (LayoutKind.Sequential, C's
// alignment); C `bool` fields are bytes here so every struct stays blittable.
// A refused call throws TandemException with the library's message.
//
// Joints: the distance joint (ropes, as in Rope.cs) with its limits, length
// and reaction force. Not wrapped yet (the C headers have them; add a
// [DllImport] line each): the other joint kinds, queries, events, replays,
// the sync test, the world profile and the session.
using System;
using System.Runtime.InteropServices;
using System.Text;

namespace Tandem {

[StructLayout(LayoutKind.Sequential)] public struct Vec2 { public long X, Y; public Vec2(long x, long y) { X = x; Y = y; } }
[StructLayout(LayoutKind.Sequential)] public struct Rot { public long C, S; }
[StructLayout(LayoutKind.Sequential)] public struct Aabb { public Vec2 Lower, Upper; }
[StructLayout(LayoutKind.Sequential)] public struct WorldId { public ushort Index1, Generation; }
[StructLayout(LayoutKind.Sequential)] public struct BodyId { public uint Index1, Generation; public WorldId World; }
[StructLayout(LayoutKind.Sequential)] public struct ShapeId { public uint Index1, Generation; public WorldId World; }
[StructLayout(LayoutKind.Sequential)] public struct JointId { public uint Index1, Generation; public WorldId World; }
/// <summary>tandem_scene_id / tandem_replay_id / tandem_recorder_id.</summary>
[StructLayout(LayoutKind.Sequential)] public struct ObjectId { public uint Index1, Generation; }

[StructLayout(LayoutKind.Sequential)]
public struct WorldDef {
  public Vec2 Gravity;
  public int SubStepCount;
  public long ContactHertz, ContactDampingRatio, MaxContactPushSpeed, JointHertz, JointDampingRatio;
  public long RestitutionThreshold, HitEventThreshold, MaxLinearSpeed;
  public Aabb Bounds;
  public byte EnableSleep, EnableContinuous;
  public int BroadPhase;
  public ulong UserData;
  /// <summary>Threads that run a step, 1…16 (results identical for every value).</summary>
  public int WorkerCount;
  /// <summary>tandem_enqueue_task_fn / tandem_finish_task_fn (function pointers, IntPtr.Zero: none) and their context.</summary>
  public IntPtr EnqueueTask, FinishTask, UserTaskContext;
  public int InternalCookie;
}

[StructLayout(LayoutKind.Sequential)]
public struct BodyDef {
  public int Type;
  public Vec2 Position;
  public Rot Rotation;
  public Vec2 LinearVelocity;
  public long AngularVelocity, LinearDamping, AngularDamping, GravityScale;
  public ulong UserData;
  public byte EnableSleep, IsAwake, FixedRotation, IsBullet, IsEnabled;
  public int InternalCookie;
}

[StructLayout(LayoutKind.Sequential)] public struct Filter { public ulong CategoryBits, MaskBits; public int GroupIndex; }

[StructLayout(LayoutKind.Sequential)]
public struct ShapeDef {
  public long Friction, Restitution, Density;
  public Filter Filter;
  public ulong UserData;
  public byte IsSensor, EnableHitEvents;
  public int InternalCookie;
}

[StructLayout(LayoutKind.Sequential)] public struct Circle { public Vec2 Center; public long Radius; }

[StructLayout(LayoutKind.Sequential)]
public struct Polygon {
  [MarshalAs(UnmanagedType.ByValArray, SizeConst = 8)] public Vec2[] Vertices;
  [MarshalAs(UnmanagedType.ByValArray, SizeConst = 8)] public Vec2[] Normals;
  public Vec2 Centroid;
  public long Radius;
  public int Count;
}

[StructLayout(LayoutKind.Sequential)]
public struct JointBaseDef {
  public BodyId BodyA, BodyB;
  public Vec2 LocalAnchorA, LocalAnchorB;
  public byte CollideConnected;
  public long BreakForce, BreakTorque;
  public ulong UserData;
}

/// <summary>tandem_distance_joint_def; a rope: EnableSpring with Hertz 0, EnableLimit, MaxLength.</summary>
[StructLayout(LayoutKind.Sequential)]
public struct DistanceJointDef {
  public JointBaseDef Base;
  public long Length;
  public byte EnableSpring;
  public long Hertz, DampingRatio;
  public byte EnableLimit;
  public long MinLength, MaxLength;
  public byte EnableMotor;
  public long MotorSpeed, MaxMotorForce;
  public int InternalCookie;
}

[StructLayout(LayoutKind.Sequential)]
public struct SceneInfo { public int StepHz; public long TimeStep; public long Ticks; public int BodyCount, InputCount; }

/// <summary>The raw C API (tandem_c.h), one declaration per function.</summary>
public static class Native {
  const string Lib = "tandem";
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern IntPtr tandem_last_error_message();
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern IntPtr tandem_status_name(int status);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_abi_version();
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern long tandem_q32_from_int(int value);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_q32_from_ratio(long num, long den, out long value);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_q32_from_text(byte[] text, out long value);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_q32_to_text(long value, byte[] text, UIntPtr capacity, out UIntPtr length);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern double tandem_q32_to_double(long value);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern WorldDef tandem_default_world_def();
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern BodyDef tandem_default_body_def();
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern ShapeDef tandem_default_shape_def();
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_create_world(ref WorldDef def, out WorldId world);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_destroy_world(WorldId world);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_world_step(WorldId world, long timeStep, out uint flags);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_world_set_worker_count(WorldId world, int workerCount);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_world_worker_count(WorldId world);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_rollback_buffer_create(out IntPtr buffer);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern void tandem_rollback_buffer_free(IntPtr buffer);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_rollback_save(WorldId world, IntPtr buffer);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_rollback_restore(WorldId world, IntPtr buffer);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern ulong tandem_rollback_hash(IntPtr buffer);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern UIntPtr tandem_rollback_image_size(IntPtr buffer);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern ulong tandem_world_state_hash(WorldId world);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_world_snapshot(WorldId world, byte[] bytes, UIntPtr capacity, out UIntPtr size);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_world_restore(WorldId world, byte[] bytes, UIntPtr size);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_create_body(WorldId world, ref BodyDef def, out BodyId body);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern Vec2 tandem_body_position(BodyId body);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_body_set_linear_velocity(BodyId body, Vec2 velocity);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_make_box(long halfWidth, long halfHeight, out Polygon polygon);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_create_polygon_shape(BodyId body, ref ShapeDef def, ref Polygon polygon, out ShapeId shape);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_create_circle_shape(BodyId body, ref ShapeDef def, ref Circle circle, out ShapeId shape);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern Vec2 tandem_body_local_point(BodyId body, Vec2 worldPoint);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern long tandem_vec2_distance(Vec2 a, Vec2 b);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern DistanceJointDef tandem_default_distance_joint_def();
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_create_distance_joint(WorldId world, ref DistanceJointDef def, out JointId joint);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_destroy_joint(JointId joint);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_joint_set_limits(JointId joint, long lower, long upper);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_joint_set_length(JointId joint, long length);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern Vec2 tandem_joint_reaction_force(JointId joint);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_scene_load_file(byte[] path, out ObjectId scene);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_scene_destroy(ObjectId scene);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_scene_get_info(ObjectId scene, out SceneInfo info);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_scene_build(ObjectId scene, out WorldId world);
  [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)] public static extern int tandem_scene_apply_inputs(ObjectId scene, WorldId world, long tick);

  /// <summary>A NUL-terminated UTF-8 string from the library.</summary>
  public static string Utf8(IntPtr p) {
    if (p == IntPtr.Zero) return "";
    int n = 0;
    while (Marshal.ReadByte(p, n) != 0) ++n;
    var bytes = new byte[n];
    Marshal.Copy(p, bytes, 0, n);
    return Encoding.UTF8.GetString(bytes);
  }

  /// <summary>NUL-terminated UTF-8 for the library.</summary>
  public static byte[] Utf8(string s) { return Encoding.UTF8.GetBytes(s + "\0"); }

  /// <summary>Throws TandemException unless status is TANDEM_OK.</summary>
  public static void Check(int status) { if (status != 0) throw new TandemException(status); }
}

/// <summary>A refused call: the status code and the library's message.</summary>
public class TandemException : Exception {
  public readonly int Status;
  public TandemException(int status)
      : base(Native.Utf8(Native.tandem_last_error_message()) + " [" + Native.Utf8(Native.tandem_status_name(status)) + "]") {
    Status = status;
  }
}

/// <summary>Exact Q32.32 helpers (raw longs).</summary>
public static class Q {
  public static long FromInt(int v) { return Native.tandem_q32_from_int(v); }
  public static long FromText(string text) { long v; Native.Check(Native.tandem_q32_from_text(Native.Utf8(text), out v)); return v; }
  public static long Ratio(long num, long den) { long v; Native.Check(Native.tandem_q32_from_ratio(num, den, out v)); return v; }
  public static string ToText(long raw) {
    UIntPtr n;
    Native.Check(Native.tandem_q32_to_text(raw, null, UIntPtr.Zero, out n));
    var buf = new byte[(int)n + 1];
    Native.Check(Native.tandem_q32_to_text(raw, buf, (UIntPtr)buf.Length, out n));
    return Encoding.UTF8.GetString(buf, 0, (int)n);
  }
  /// <summary>For display only.</summary>
  public static double ToDouble(long raw) { return Native.tandem_q32_to_double(raw); }
}

/// <summary>A physics world; Dispose() destroys it.</summary>
public sealed class World : IDisposable {
  public WorldId Id;
  public World() { var def = Native.tandem_default_world_def(); Native.Check(Native.tandem_create_world(ref def, out Id)); }
  public World(WorldId id) { Id = id; }
  public void Dispose() { if (Id.Index1 != 0) { Native.Check(Native.tandem_destroy_world(Id)); Id = new WorldId(); } }
  public uint Step(long timeStep) { uint flags; Native.Check(Native.tandem_world_step(Id, timeStep, out flags)); return flags; }
  public ulong StateHash() { return Native.tandem_world_state_hash(Id); }
  public Body CreateBody(BodyDef def) { BodyId b; Native.Check(Native.tandem_create_body(Id, ref def, out b)); return new Body(b); }
  public byte[] Snapshot() {
    UIntPtr n;
    Native.Check(Native.tandem_world_snapshot(Id, null, UIntPtr.Zero, out n));
    var bytes = new byte[(int)n];
    Native.Check(Native.tandem_world_snapshot(Id, bytes, (UIntPtr)bytes.Length, out n));
    return bytes;
  }
  public void Restore(byte[] image) { Native.Check(Native.tandem_world_restore(Id, image, (UIntPtr)image.Length)); }
  public Joint CreateDistanceJoint(DistanceJointDef def) {
    JointId j;
    Native.Check(Native.tandem_create_distance_joint(Id, ref def, out j));
    return new Joint(j);
  }
}

/// <summary>A joint handle (a value); Index1 0 is null.</summary>
public struct Joint {
  public JointId Id;
  public Joint(JointId id) { Id = id; }
  public bool IsNull { get { return Id.Index1 == 0; } }
  public void SetLimits(long lower, long upper) { Native.Check(Native.tandem_joint_set_limits(Id, lower, upper)); }
  public void SetLength(long length) { Native.Check(Native.tandem_joint_set_length(Id, length)); }
  /// <summary>Force on body B during the last sub-step, N (raw Q32.32).</summary>
  public Vec2 ReactionForce { get { return Native.tandem_joint_reaction_force(Id); } }
  public void Destroy() { Native.Check(Native.tandem_destroy_joint(Id)); Id = new JointId(); }
}

/// <summary>A body handle (a value).</summary>
public struct Body {
  public BodyId Id;
  public Body(BodyId id) { Id = id; }
  public Vec2 Position { get { return Native.tandem_body_position(Id); } }
  public Vec2 LocalPoint(Vec2 worldPoint) { return Native.tandem_body_local_point(Id, worldPoint); }
  public ShapeId AddBox(long halfWidth, long halfHeight) {
    Polygon box;
    Native.Check(Native.tandem_make_box(halfWidth, halfHeight, out box));
    var def = Native.tandem_default_shape_def();
    ShapeId s;
    Native.Check(Native.tandem_create_polygon_shape(Id, ref def, ref box, out s));
    return s;
  }
  public ShapeId AddCircle(long radius) {
    var circle = new Circle { Center = new Vec2(0, 0), Radius = radius };
    var def = Native.tandem_default_shape_def();
    ShapeId s;
    Native.Check(Native.tandem_create_circle_shape(Id, ref def, ref circle, out s));
    return s;
  }
}

/// <summary>A JSON scene file; Dispose() frees it.</summary>
public sealed class Scene : IDisposable {
  public ObjectId Id;
  public SceneInfo Info;
  public Scene(string path) {
    Native.Check(Native.tandem_scene_load_file(Native.Utf8(path), out Id));
    Native.Check(Native.tandem_scene_get_info(Id, out Info));
  }
  public World Build() { WorldId w; Native.Check(Native.tandem_scene_build(Id, out w)); return new World(w); }
  /// <summary>Applies the inputs scripted for `tick`, then steps once.</summary>
  public void Step(World world, long tick) {
    Native.Check(Native.tandem_scene_apply_inputs(Id, world.Id, tick));
    world.Step(Info.TimeStep);
  }
  public void Dispose() { if (Id.Index1 != 0) { Native.Check(Native.tandem_scene_destroy(Id)); Id = new ObjectId(); } }
}

}  // namespace Tandem
