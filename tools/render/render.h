// render.h — draws a world to PNG or SVG with Cairo (tools only; binary
// floating point is fine here: nothing flows back into the simulation).
//
// What is drawn: every shape of every live body, filled and outlined by body
// type (static green-grey, kinematic blue, dynamic orange; sleeping bodies
// grey, disabled ones hollow; sensors dashed outlines), a radius line on
// circles so rotation shows, joints (origin–anchor–anchor–origin lines,
// coloured by kind; a mouse joint from its target), and optionally each
// shape's AABB and each
// contact's points and normal. Everything is read through the debug-draw
// callbacks (physics/debug_draw.h, world_draw), never from the world's
// internals; the renderer never changes the world.
//
// A View maps world metres to the picture; fit_view() frames every shape.
// A ContactSheet lays several frames out in one PNG grid.
#pragma once

#include <memory>
#include <string>

#include "physics/tandem.h"

namespace tandem::render {

/// The world-space rectangle shown, m (y up).
struct View {
  double min_x = -10, min_y = -10, max_x = 10, max_y = 10;
};

/// What to draw and how big.
struct RenderOptions {
  int width = 800;        ///< pixels
  int height = 600;       ///< pixels
  bool aabbs = false;     ///< draw each shape's world AABB
  bool contacts = false;  ///< draw contact points and normals
  bool joints = true;     ///< draw joints: body origin → anchor A → anchor B → body origin (joint.h)
  std::string caption;    ///< text in the top-left corner (e.g. "tick 120")
};

/// A view around every shape's AABB plus a margin (fraction of the size).
/// Shapes farther than `clip` metres from the origin are ignored, so a huge
/// ground does not shrink everything else. An empty world gives ±10 m.
View fit_view(WorldId world, double margin = 0.05, double clip = 1000.0);

/// Writes one PNG. Returns an empty string, or an error naming the path.
std::string render_png(WorldId world, const View& view, const RenderOptions& options, const std::string& path);
/// Writes one SVG. Returns an empty string, or an error naming the path.
std::string render_svg(WorldId world, const View& view, const RenderOptions& options, const std::string& path);

/// Several frames side by side in one PNG: `columns` per row, each cell
/// options.width × options.height pixels, rows added as needed.
class ContactSheet {
 public:
  ContactSheet(int columns, int cell_width, int cell_height);
  ~ContactSheet();
  ContactSheet(const ContactSheet&) = delete;
  ContactSheet& operator=(const ContactSheet&) = delete;
  /// Draws the world into the next cell.
  void add(WorldId world, const View& view, const RenderOptions& options);
  /// Writes the sheet. Returns an empty string, or an error naming the path.
  std::string write_png(const std::string& path) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tandem::render
