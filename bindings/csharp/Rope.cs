// Rope.cs — the README's grappling hook from C#: a ball hangs from a ceiling
// on a rope (a distance joint with a 0 Hz spring and a maximum length) shot
// at tick 5, reeled in 5 cm a tick for ticks 120…199 and released at tick
// 300. It prints "rope tick N hash 0x..." every 60 ticks; ctest capi/csharp
// checks the lines equal the C++ version's (capi/tests/rope_native.cpp).
//   mcs -out:Rope.exe Tandem.cs Rope.cs && LD_LIBRARY_PATH=<lib dir> mono Rope.exe
using System;
using Tandem;

static class Rope {
  static int Main() {
    using (var world = new World()) {
      var ceilingDef = Native.tandem_default_body_def();
      ceilingDef.Position = new Vec2(0, Q.FromInt(10));
      Body ceiling = world.CreateBody(ceilingDef);
      var playerDef = Native.tandem_default_body_def();
      playerDef.Type = 2;  // TANDEM_BODY_DYNAMIC
      playerDef.Position = new Vec2(Q.FromInt(-4), Q.FromInt(3));
      Body player = world.CreateBody(playerDef);
      player.AddCircle(Q.FromText("0.4"));

      var hook = new Joint();   // null: not attached
      long rope = 0;            // current rope length, raw Q32.32 m
      long one = Q.FromInt(1), twenty = Q.FromInt(20), reelStep = Q.Ratio(-5, 100), dt = Q.Ratio(1, 60);
      for (int tick = 0; tick < 420; ++tick) {
        var aim = new Vec2(0, Q.FromInt(10));
        if (tick == 5 && hook.IsNull) {  // fire: attach at the current distance
          var def = Native.tandem_default_distance_joint_def();
          def.Base.BodyA = ceiling.Id;
          def.Base.BodyB = player.Id;
          def.Base.LocalAnchorA = ceiling.LocalPoint(aim);
          rope = Math.Max(Native.tandem_vec2_distance(aim, player.Position), one);
          def.Length = rope;
          def.EnableSpring = 1;  // hertz 0: no spring force, a free rope...
          def.EnableLimit = 1;   // ...that never gets longer than MaxLength
          def.MaxLength = rope;
          hook = world.CreateDistanceJoint(def);
        }
        if (!hook.IsNull && tick >= 120 && tick < 200) {  // reel in, between 1 m and 20 m
          rope = Math.Min(Math.Max(rope + reelStep, one), twenty);  // raw addition: exact here
          hook.SetLimits(0, rope);
        }
        if (tick == 300 && !hook.IsNull) hook.Destroy();
        world.Step(dt);
        if ((tick + 1) % 60 == 0) Console.WriteLine("rope tick {0} hash 0x{1:x16}", tick + 1, world.StateHash());
      }
    }
    return 0;
  }
}
