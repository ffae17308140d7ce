// render.cpp — Cairo drawing of a world (see render.h).
#include "render.h"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "physics/debug_draw.h"

// Fontconfig (under Cairo's text) keeps its configuration cache until exit
// on purpose; LeakSanitizer would report it in sanitizer builds.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TANDEM_RENDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(TANDEM_RENDER_ASAN)
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }
#endif

namespace tandem::render {
namespace {

struct Color {
  double r, g, b;
};

// World → pixel mapping for one cell.
struct Mapper {
  double scale = 1, ox = 0, oy = 0;  // pixel = (ox + x·scale, oy − y·scale)
  Mapper(const View& v, double x0, double y0, double w, double h) {
    const double vw = std::max(v.max_x - v.min_x, 1e-9), vh = std::max(v.max_y - v.min_y, 1e-9);
    scale = std::min(w / vw, h / vh);
    const double cx = 0.5 * (v.min_x + v.max_x), cy = 0.5 * (v.min_y + v.max_y);
    ox = x0 + 0.5 * w - cx * scale;
    oy = y0 + 0.5 * h + cy * scale;
  }
  double x(double wx) const { return ox + wx * scale; }
  double y(double wy) const { return oy - wy * scale; }
};

double d(Q32 v) { return v.to_double(); }

// A Cairo drawer behind world_draw() (physics/debug_draw.h): world points
// come as Q32 metres and are mapped to pixels here (display only).
struct Painter {
  cairo_t* cr;
  const Mapper& m;
};

Color state_color(DrawBodyState state) {
  switch (state) {
    case DrawBodyState::disabled: return {0.85, 0.85, 0.85};
    case DrawBodyState::static_body: return {0.55, 0.65, 0.55};
    case DrawBodyState::kinematic_body: return {0.55, 0.6, 0.9};
    case DrawBodyState::asleep: return {0.7, 0.7, 0.7};
    case DrawBodyState::awake: break;
  }
  return {0.95, 0.65, 0.35};
}

// Fills (solid shapes of enabled bodies, not sensors) and outlines the
// current path in the body's colours; sensors dashed.
void finish_shape(cairo_t* cr, const DrawShape& s, bool solid) {
  const Color c = state_color(s.state);
  if (s.sensor) {
    const double dash[] = {4.0, 3.0};
    cairo_set_dash(cr, dash, 2, 0);
  }
  if (solid && !s.sensor && s.state != DrawBodyState::disabled) {
    cairo_set_source_rgba(cr, c.r, c.g, c.b, 0.85);
    cairo_fill_preserve(cr);
  }
  cairo_set_source_rgb(cr, c.r * 0.45, c.g * 0.45, c.b * 0.45);
  cairo_set_line_width(cr, solid ? 1.0 : 2.0);
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0);
}

void paint_circle(Vec2 center, Q32 radius, Vec2 rim, const DrawShape& s, void* context) {
  const Painter& p = *static_cast<const Painter*>(context);
  cairo_new_path(p.cr);
  cairo_new_sub_path(p.cr);
  cairo_arc(p.cr, p.m.x(d(center.x)), p.m.y(d(center.y)), d(radius) * p.m.scale, 0, 2 * M_PI);
  finish_shape(p.cr, s, true);
  // radius line: shows rotation
  cairo_move_to(p.cr, p.m.x(d(center.x)), p.m.y(d(center.y)));
  cairo_line_to(p.cr, p.m.x(d(rim.x)), p.m.y(d(rim.y)));
  cairo_stroke(p.cr);
}

void paint_capsule(Vec2 c1, Vec2 c2, Q32 radius, const DrawShape& s, void* context) {
  const Painter& p = *static_cast<const Painter*>(context);
  const double x1 = d(c1.x), y1 = d(c1.y), x2 = d(c2.x), y2 = d(c2.y);
  const double a = std::atan2(-(y2 - y1), x2 - x1);  // screen angle (y down)
  const double r = d(radius) * p.m.scale;
  cairo_new_path(p.cr);
  cairo_new_sub_path(p.cr);
  cairo_arc(p.cr, p.m.x(x2), p.m.y(y2), r, a - M_PI / 2, a + M_PI / 2);
  cairo_arc(p.cr, p.m.x(x1), p.m.y(y1), r, a + M_PI / 2, a + 3 * M_PI / 2);
  cairo_close_path(p.cr);
  finish_shape(p.cr, s, true);
}

void paint_polygon(const Vec2* vertices, int32_t count, Q32, const DrawShape& s, void* context) {
  const Painter& p = *static_cast<const Painter*>(context);
  cairo_new_path(p.cr);
  cairo_new_sub_path(p.cr);
  for (int32_t i = 0; i < count; ++i) {
    const double x = p.m.x(d(vertices[i].x)), y = p.m.y(d(vertices[i].y));
    if (i == 0) cairo_move_to(p.cr, x, y);
    else cairo_line_to(p.cr, x, y);
  }
  cairo_close_path(p.cr);
  finish_shape(p.cr, s, true);
}

void paint_segment(Vec2 a, Vec2 b, const DrawShape& s, void* context) {
  const Painter& p = *static_cast<const Painter*>(context);
  cairo_new_path(p.cr);
  cairo_move_to(p.cr, p.m.x(d(a.x)), p.m.y(d(a.y)));
  cairo_line_to(p.cr, p.m.x(d(b.x)), p.m.y(d(b.y)));
  finish_shape(p.cr, s, false);
}

void paint_aabb(const AABB& box, const DrawShape&, void* context) {
  const Painter& p = *static_cast<const Painter*>(context);
  cairo_set_source_rgba(p.cr, 0.8, 0.2, 0.8, 0.6);
  cairo_set_line_width(p.cr, 0.7);
  cairo_rectangle(p.cr, p.m.x(d(box.lower.x)), p.m.y(d(box.upper.y)), d(box.upper.x - box.lower.x) * p.m.scale,
                  d(box.upper.y - box.lower.y) * p.m.scale);
  cairo_stroke(p.cr);
}

// Joints: body origin → anchor A → anchor B → body origin, coloured by kind
// (a mouse joint from its target; a distance joint anchor to anchor).
void paint_joint(JointId, JointType type, Vec2 oa, Vec2 a, Vec2 b, Vec2 ob, void* context) {
  const Painter& p = *static_cast<const Painter*>(context);
  cairo_t* cr = p.cr;
  static const Color k_joint_colors[] = {{0.1, 0.5, 0.1}, {0.1, 0.6, 0.7}, {0.4, 0.4, 0.4}, {0.6, 0.2, 0.6},
                                         {0.8, 0.1, 0.1}, {0.2, 0.3, 0.8}, {0.7, 0.5, 0.1}};
  const Color c = k_joint_colors[static_cast<size_t>(type)];
  cairo_set_source_rgba(cr, c.r, c.g, c.b, 0.9);
  cairo_set_line_width(cr, 1.5);
  if (type != JointType::mouse && type != JointType::distance) {
    cairo_move_to(cr, p.m.x(d(oa.x)), p.m.y(d(oa.y)));
    cairo_line_to(cr, p.m.x(d(a.x)), p.m.y(d(a.y)));
  } else {
    cairo_move_to(cr, p.m.x(d(a.x)), p.m.y(d(a.y)));
  }
  cairo_line_to(cr, p.m.x(d(b.x)), p.m.y(d(b.y)));
  if (type != JointType::distance) cairo_line_to(cr, p.m.x(d(ob.x)), p.m.y(d(ob.y)));
  cairo_stroke(cr);
  for (const Vec2 q : {a, b}) {
    cairo_arc(cr, p.m.x(d(q.x)), p.m.y(d(q.y)), 2.5, 0, 2 * M_PI);
    cairo_fill(cr);
  }
}

// Contact points (red touching, blue speculative) and their normals.
void paint_contact(Vec2 point, Vec2 normal, Q32 separation, void* context) {
  const Painter& p = *static_cast<const Painter*>(context);
  cairo_t* cr = p.cr;
  const double normal_px = 12.0;
  const double px = p.m.x(d(point.x)), py = p.m.y(d(point.y));
  const bool touching = separation <= Q32{};
  cairo_set_source_rgb(cr, touching ? 0.85 : 0.4, 0.1, touching ? 0.1 : 0.85);
  cairo_arc(cr, px, py, 2.5, 0, 2 * M_PI);
  cairo_fill(cr);
  cairo_set_line_width(cr, 1.0);
  cairo_move_to(cr, px, py);
  cairo_line_to(cr, px + d(normal.x) * normal_px, py - d(normal.y) * normal_px);
  cairo_stroke(cr);
}

void draw_world(cairo_t* cr, WorldId world, const View& view, const RenderOptions& o, double x0, double y0, double w,
                double h) {
  cairo_save(cr);
  cairo_rectangle(cr, x0, y0, w, h);
  cairo_clip(cr);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const Mapper m(view, x0, y0, w, h);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);

  Painter painter{cr, m};
  DebugDraw dd;
  dd.context = &painter;
  dd.draw_aabbs = o.aabbs;
  dd.draw_joints = o.joints;
  dd.draw_contacts = o.contacts;
  dd.draw_polygon = paint_polygon;
  dd.draw_circle = paint_circle;
  dd.draw_capsule = paint_capsule;
  dd.draw_segment = paint_segment;
  dd.draw_aabb = paint_aabb;
  dd.draw_joint = paint_joint;
  dd.draw_contact = paint_contact;
  (void)world_draw(world, dd);  // an invalid world draws nothing (a blank frame), as before

  if (!o.caption.empty()) {
    cairo_select_font_face(cr, "monospace", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 13);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_move_to(cr, x0 + 6, y0 + 17);
    cairo_show_text(cr, o.caption.c_str());
  }
  cairo_set_source_rgb(cr, 0.75, 0.75, 0.75);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, x0 + 0.5, y0 + 0.5, w - 1, h - 1);
  cairo_stroke(cr);
  cairo_restore(cr);
}

std::string cairo_error(cairo_status_t status, const std::string& path) {
  return path + ": cannot write the picture (" + cairo_status_to_string(status) + ")";
}

}  // namespace

View fit_view(WorldId world, double margin, double clip) {
  const int32_t body_count = world_bodies(world, nullptr, 0);
  std::vector<BodyId> bodies(static_cast<size_t>(body_count));
  world_bodies(world, bodies.data(), body_count);
  bool any = false;
  View v;
  std::vector<ShapeId> shapes;
  for (BodyId b : bodies) {
    shapes.resize(static_cast<size_t>(body_shape_count(b)));
    body_shapes(b, shapes.data(), static_cast<int32_t>(shapes.size()));
    for (ShapeId s : shapes) {
      const AABB box = shape_aabb(s);
      const double lx = std::max(d(box.lower.x), -clip), ly = std::max(d(box.lower.y), -clip);
      const double ux = std::min(d(box.upper.x), clip), uy = std::min(d(box.upper.y), clip);
      if (lx > ux || ly > uy) continue;
      if (!any) v = View{lx, ly, ux, uy}, any = true;
      v.min_x = std::min(v.min_x, lx), v.min_y = std::min(v.min_y, ly);
      v.max_x = std::max(v.max_x, ux), v.max_y = std::max(v.max_y, uy);
    }
  }
  if (!any) return View{};
  const double mx = (v.max_x - v.min_x) * margin + 0.1, my = (v.max_y - v.min_y) * margin + 0.1;
  return View{v.min_x - mx, v.min_y - my, v.max_x + mx, v.max_y + my};
}

std::string render_png(WorldId world, const View& view, const RenderOptions& options, const std::string& path) {
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, options.width, options.height);
  cairo_t* cr = cairo_create(surface);
  draw_world(cr, world, view, options, 0, 0, options.width, options.height);
  cairo_destroy(cr);
  const cairo_status_t status = cairo_surface_write_to_png(surface, path.c_str());
  cairo_surface_destroy(surface);
  return status == CAIRO_STATUS_SUCCESS ? "" : cairo_error(status, path);
}

std::string render_svg(WorldId world, const View& view, const RenderOptions& options, const std::string& path) {
  cairo_surface_t* surface = cairo_svg_surface_create(path.c_str(), options.width, options.height);
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    const cairo_status_t status = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    return cairo_error(status, path);
  }
  cairo_t* cr = cairo_create(surface);
  draw_world(cr, world, view, options, 0, 0, options.width, options.height);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  const cairo_status_t status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  return status == CAIRO_STATUS_SUCCESS ? "" : cairo_error(status, path);
}

struct ContactSheet::Impl {
  int columns, cell_w, cell_h, count = 0;
  std::vector<cairo_surface_t*> frames;
};

ContactSheet::ContactSheet(int columns, int cell_width, int cell_height)
    : impl_(new Impl{std::max(1, columns), cell_width, cell_height, 0, {}}) {}

ContactSheet::~ContactSheet() {
  for (cairo_surface_t* s : impl_->frames) cairo_surface_destroy(s);
}

void ContactSheet::add(WorldId world, const View& view, const RenderOptions& options) {
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, impl_->cell_w, impl_->cell_h);
  cairo_t* cr = cairo_create(surface);
  draw_world(cr, world, view, options, 0, 0, impl_->cell_w, impl_->cell_h);
  cairo_destroy(cr);
  impl_->frames.push_back(surface);
}

std::string ContactSheet::write_png(const std::string& path) const {
  const int n = static_cast<int>(impl_->frames.size());
  const int cols = std::min(impl_->columns, std::max(1, n));
  const int rows = std::max(1, (n + cols - 1) / cols);
  cairo_surface_t* sheet = cairo_image_surface_create(CAIRO_FORMAT_RGB24, cols * impl_->cell_w, rows * impl_->cell_h);
  cairo_t* cr = cairo_create(sheet);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  for (int i = 0; i < n; ++i) {
    cairo_set_source_surface(cr, impl_->frames[static_cast<size_t>(i)], (i % cols) * impl_->cell_w,
                             (i / cols) * impl_->cell_h);
    cairo_paint(cr);
  }
  cairo_destroy(cr);
  const cairo_status_t status = cairo_surface_write_to_png(sheet, path.c_str());
  cairo_surface_destroy(sheet);
  return status == CAIRO_STATUS_SUCCESS ? "" : cairo_error(status, path);
}

}  // namespace tandem::render
