// Hello.cs — Tandem from C#, the way a Unity project would call it: the same
// world as capi/examples/hello.c (ctest capi/csharp checks that the hashes
// are the C example's), then, given a scene file, that scene run to its end
// (its final hash must be `tandem run`'s).
//   mcs -out:Hello.exe Tandem.cs Hello.cs && LD_LIBRARY_PATH=<lib dir> mono Hello.exe [scene.json]
using System;
using System.Globalization;
using Tandem;

static class Hello {
  static int Main(string[] args) {
    if (Native.tandem_abi_version() != 4) { Console.Error.WriteLine("unexpected libtandem ABI"); return 1; }
    using (var world = new World()) {
      var groundDef = Native.tandem_default_body_def();
      world.CreateBody(groundDef).AddBox(Q.FromInt(20), Q.FromInt(1));
      long half = Q.FromText("0.5");
      for (int i = 0; i < 5; ++i) {
        var def = Native.tandem_default_body_def();
        def.Type = 2;  // TANDEM_BODY_DYNAMIC
        def.Position.Y = Q.FromInt(2 + i);
        world.CreateBody(def).AddBox(half, half);
      }
      var ballDef = Native.tandem_default_body_def();
      ballDef.Type = 2;
      ballDef.Position = new Vec2(Q.FromInt(-6), Q.FromInt(3));
      ballDef.LinearVelocity.X = Q.FromInt(8);
      Body ball = world.CreateBody(ballDef);
      ball.AddCircle(half);

      long dt = Q.Ratio(1, 60);
      byte[] atOneSecond = null;
      for (int tick = 1; tick <= 120; ++tick) {
        world.Step(dt);
        if (tick % 60 == 0) {
          Console.WriteLine(string.Format(CultureInfo.InvariantCulture, "tick {0} hash 0x{1:x16} ball x {2:F3} m", tick,
                                          world.StateHash(), Q.ToDouble(ball.Position.X)));
        }
        if (tick == 60) atOneSecond = world.Snapshot();
      }
      // Roll back one second and re-run it: the same hash (rollback netcode's core).
      ulong final = world.StateHash();
      world.Restore(atOneSecond);
      for (int tick = 61; tick <= 120; ++tick) world.Step(dt);
      if (world.StateHash() != final) { Console.Error.WriteLine("rollback gave a different hash"); return 1; }
      Console.WriteLine("rollback ok, x = " + Q.ToText(ball.Position.X) + " m exactly");
    }
    if (args.Length > 0) {
      using (var scene = new Scene(args[0]))
      using (var world = scene.Build()) {
        for (long tick = 0; tick < scene.Info.Ticks; ++tick) scene.Step(world, tick);
        Console.WriteLine(string.Format("scene final: tick {0}, hash 0x{1:x16}", scene.Info.Ticks, world.StateHash()));
      }
    }
    try {
      Q.FromText("1.2x");
      return 1;
    } catch (TandemException e) {
      Console.WriteLine("error as expected: " + e.Message);
    }
    return 0;
  }
}
