// NFF reader. Follows rtprof's parser (tracer/src/nff.rs) in what it accepts: `#`
// comments, blank lines, the view block's lines in any order, `c` on one line (as the
// SPD generators and rtprof's writer print it) or on three, and the same checks of
// ranges and degenerate shapes, so that a file rtprof refuses is refused here too.

#include "nff.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace {

constexpr float MAX_COORDINATE = 1e9f;  // rtprof's nff::MAX_COORDINATE
constexpr float MAX_COEFFICIENT = 1000.0f;

struct Line {
  int number = 0;
  std::vector<std::string> tokens;
};

class Reader {
 public:
  explicit Reader(std::istream& in) : in_(in) {}

  // The next line with at least one token (comments removed); false at the end.
  bool next(Line& line) {
    if (have_peeked_) {
      have_peeked_ = false;
      line = peeked_;
      return true;
    }
    std::string raw;
    while (std::getline(in_, raw)) {
      ++number_;
      auto hash = raw.find('#');
      if (hash != std::string::npos) raw.resize(hash);
      std::istringstream words(raw);
      line.tokens.clear();
      for (std::string w; words >> w;) line.tokens.push_back(w);
      if (!line.tokens.empty()) {
        line.number = number_;
        last_ = number_;
        return true;
      }
    }
    return false;
  }

  // The next line's first token without consuming the line ("" at the end).
  std::string peek() {
    if (!have_peeked_) {
      if (!next(peeked_)) return "";
      have_peeked_ = true;
    }
    return peeked_.tokens[0];
  }

  Line required(const std::string& what) {
    Line line;
    if (!next(line)) throw NffError(last_, "unexpected end of file: expected " + what);
    return line;
  }

  int last() const { return last_; }

 private:
  std::istream& in_;
  int number_ = 0, last_ = 1;
  bool have_peeked_ = false;
  Line peeked_;
};

float number(int line, const std::string& token, const std::string& what) {
  errno = 0;
  char* end = nullptr;
  float v = std::strtof(token.c_str(), &end);
  if (end == token.c_str() || *end != '\0')
    throw NffError(line, "'" + token + "' is not a number (expected " + what + ")");
  if (!std::isfinite(v))
    throw NffError(line, "'" + token + "' is not a finite number (expected " + what + ")");
  return v;
}

// Exactly `n` numbers from `tokens[first..]`.
std::vector<float> numbers(const Line& l, size_t first, size_t n, const std::string& what) {
  size_t found = l.tokens.size() - first;
  if (found != n)
    throw NffError(l.number, "expected " + std::to_string(n) + " numbers (" + what +
                                 "), found " + std::to_string(found) + " values");
  std::vector<float> out;
  for (size_t i = first; i < l.tokens.size(); ++i) out.push_back(number(l.number, l.tokens[i], what));
  return out;
}

std::vector<float> coordinates(const Line& l, size_t first, size_t n, const std::string& what) {
  auto v = numbers(l, first, n, what);
  for (float x : v)
    if (!(std::fabs(x) <= MAX_COORDINATE))
      throw NffError(l.number, "a value beyond the supported coordinate range ±1e9 (expected " + what + ")");
  return v;
}

float coefficient(int line, float v, const std::string& what) {
  if (!(v >= 0 && v <= MAX_COEFFICIENT))
    throw NffError(line, what + " must lie between 0 and 1000");
  return v;
}

Vec3 vec(const std::vector<float>& v, size_t at = 0) { return {v[at], v[at + 1], v[at + 2]}; }

// rtprof's PlanarOutline::new: the unit normal of the first three vertices, refused
// when they are collinear within f32 precision.
bool plane_normal(const std::vector<Vec3>& v, Vec3& normal) {
  Vec3 e1 = v[1] - v[0], e2 = v[2] - v[0];
  Vec3 n = cross(e1, e2);
  float n_sq = dot(n, n);
  float scale = dot(e1, e1) * dot(e2, e2);
  if (!(n_sq > 1e-12f * scale) || !std::isfinite(n_sq)) return false;
  normal = normalize(n);
  return true;
}

// rtprof's patch normal: unit length, a zero vector refused (a tiny or huge one first
// divided by its largest component).
bool unit_normal(Vec3 n, Vec3& out) {
  float len_sq = dot(n, n);
  if (len_sq >= 1.17549435e-38f && std::isfinite(len_sq)) {
    out = normalize(n);
    return true;
  }
  float largest = max_abs(n);
  if (!(largest > 0) || !std::isfinite(largest)) return false;
  out = normalize(Vec3{n.x / largest, n.y / largest, n.z / largest});
  return true;
}

View view_block(Reader& r, int v_line) {
  View view;
  bool from = false, at = false, up = false, angle = false, resolution = false;
  const std::string keys[] = {"from", "at", "up", "angle", "hither", "resolution"};
  for (;;) {
    std::string key = r.peek();
    bool known = false;
    for (auto& k : keys) known |= key == k;
    if (!known) break;
    Line l;
    r.next(l);
    if (key == "from") {
      view.from = vec(coordinates(l, 1, 3, "eye position x y z")), from = true;
    } else if (key == "at") {
      view.at = vec(coordinates(l, 1, 3, "look-at point x y z")), at = true;
    } else if (key == "up") {
      view.up = vec(coordinates(l, 1, 3, "up vector x y z")), up = true;
    } else if (key == "angle") {
      view.angle_deg = numbers(l, 1, 1, "field of view in degrees")[0];
      if (!(view.angle_deg > 0 && view.angle_deg < 180))
        throw NffError(l.number, "angle must be between 0 and 180 degrees");
      angle = true;
    } else if (key == "hither") {
      numbers(l, 1, 1, "hither distance");  // kept by rtprof, never used to clip
    } else {
      if (l.tokens.size() != 3)
        throw NffError(l.number, "expected 2 whole numbers (resolution width height)");
      char* end = nullptr;
      long w = std::strtol(l.tokens[1].c_str(), &end, 10);
      bool ok = *end == '\0';
      long h = std::strtol(l.tokens[2].c_str(), &end, 10);
      ok &= *end == '\0';
      if (!ok || w <= 0 || h <= 0)
        throw NffError(l.number, "resolution must be two positive whole numbers");
      view.width = int(w), view.height = int(h), resolution = true;
    }
  }
  const char* missing = !from ? "from" : !at ? "at" : !up ? "up" : !angle ? "angle"
                      : !resolution ? "resolution" : nullptr;
  if (missing) throw NffError(v_line, std::string("the view block has no '") + missing + "' line");
  // rtprof's check_view_basis: a direction, and an up vector across it.
  Vec3 forward = view.at - view.from;
  float f_sq = dot(forward, forward);
  if (!(f_sq > 0)) throw NffError(v_line, "'from' and 'at' are the same point");
  Vec3 side = cross(forward, view.up);
  if (!(dot(side, side) > 1e-10f * f_sq * dot(view.up, view.up)))
    throw NffError(v_line, "the 'up' vector is parallel to the view direction (or zero)");
  return view;
}

}  // namespace

Scene read_nff(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw NffError(0, "cannot open the file");
  Reader r(file);
  Scene s;
  bool have_view = false;
  std::vector<bool> light_given;
  // The material of the next primitive: the last `f`, or the default one.
  auto material = [&s]() {
    if (s.materials.empty()) s.materials.push_back(Material{});
    return unsigned(s.materials.size() - 1);
  };
  for (Line l; r.next(l);) {
    const std::string& key = l.tokens[0];
    int n = l.number;
    if (key == "v") {
      if (have_view) throw NffError(n, "second view block");
      if (l.tokens.size() != 1) throw NffError(n, "unexpected text after 'v'");
      s.view = view_block(r, n);
      have_view = true;
    } else if (key == "b") {
      auto c = numbers(l, 1, 3, "background colour r g b");
      s.background = Rgb(coefficient(n, c[0], "background colour channel"),
                         coefficient(n, c[1], "background colour channel"),
                         coefficient(n, c[2], "background colour channel"));
    } else if (key == "l") {
      if (l.tokens.size() != 4 && l.tokens.size() != 7)
        throw NffError(n, "expected 3 numbers (light x y z) or 6 (x y z r g b)");
      Light light;
      Line position{n, {l.tokens.begin(), l.tokens.begin() + 4}};
      light.position = vec(coordinates(position, 1, 3, "light position x y z"));
      light.color = Rgb::gray(1);
      bool given = l.tokens.size() == 7;
      if (given) {
        auto c = numbers(Line{n, {l.tokens[0], l.tokens[4], l.tokens[5], l.tokens[6]}}, 1, 3,
                         "light colour r g b");
        light.color = Rgb(coefficient(n, c[0], "light colour channel"),
                          coefficient(n, c[1], "light colour channel"),
                          coefficient(n, c[2], "light colour channel"));
      }
      s.lights.push_back(light);
      light_given.push_back(given);
    } else if (key == "f") {
      auto f = numbers(l, 1, 8, "material r g b Kd Ks Shine T index_of_refraction");
      Material m;
      m.color = Rgb(coefficient(n, f[0], "material colour channel"),
                    coefficient(n, f[1], "material colour channel"),
                    coefficient(n, f[2], "material colour channel"));
      m.kd = coefficient(n, f[3], "diffuse coefficient Kd");
      m.ks = coefficient(n, f[4], "specular coefficient Ks");
      m.shine = f[5];
      if (!(m.shine >= 0)) throw NffError(n, "Phong exponent Shine must not be negative");
      m.t = coefficient(n, f[6], "transmittance T");
      m.ior = f[7];
      // SPD files write ior 0 for opaque materials; only a transmitter uses it.
      if (m.t > 0 && !(m.ior >= 0.01f && m.ior <= 100.0f))
        throw NffError(n, "index of refraction of a transmitting material must lie between 0.01 and 100");
      s.materials.push_back(m);
    } else if (key == "s") {
      auto v = coordinates(l, 1, 4, "sphere centre x y z and radius");
      s.spheres.push_back({vec(v), v[3], material()});
    } else if (key == "c") {
      std::vector<float> v;
      if (l.tokens.size() == 1) {
        auto base = r.required("cone base line 'x y z radius'");
        auto b = coordinates(base, 0, 4, "cone base x y z radius");
        auto apex = r.required("cone apex line 'x y z radius'");
        auto a = coordinates(apex, 0, 4, "cone apex x y z radius");
        v = b;
        v.insert(v.end(), a.begin(), a.end());
      } else {
        v = coordinates(l, 1, 8, "cone base x y z radius and apex x y z radius");
      }
      Cone c{vec(v, 0), vec(v, 4), v[3], v[7], material()};
      Vec3 axis = c.apex - c.base;
      if (!(dot(axis, axis) > 0)) throw NffError(n, "invalid cone: base and apex are the same point");
      s.cones.push_back(c);
    } else if (key == "p" || key == "pp") {
      bool patch = key == "pp";
      const char* what = patch ? "patch" : "polygon";
      if (l.tokens.size() != 2) throw NffError(n, std::string("expected the ") + what + "'s vertex count");
      char* end = nullptr;
      long count = std::strtol(l.tokens[1].c_str(), &end, 10);
      if (*end != '\0') throw NffError(n, "'" + l.tokens[1] + "' is not a whole number (expected the vertex count)");
      if (count < 3) throw NffError(n, std::string("a ") + what + " needs at least 3 vertices");
      if (count > 65536) throw NffError(n, std::string(what) + " vertex count exceeds 65536");
      Polygon p;
      for (long i = 0; i < count; ++i) {
        auto vl = r.required(std::string(what) + " vertex " + std::to_string(i + 1) + " of " +
                             std::to_string(count));
        auto v = coordinates(vl, 0, patch ? 6 : 3, patch ? "patch vertex x y z nx ny nz" : "polygon vertex x y z");
        p.vertices.push_back(vec(v));
        if (patch) {
          Vec3 unit;
          if (!unit_normal(vec(v, 3), unit)) throw NffError(n, "invalid patch: a vertex normal is zero");
          p.normals.push_back(unit);
        }
      }
      if (!plane_normal(p.vertices, p.normal))
        throw NffError(n, std::string("invalid ") + what + ": its first three vertices are collinear");
      p.material = material();
      s.polygons.push_back(std::move(p));
    } else {
      throw NffError(n, "unknown keyword '" + key + "' (expected one of v, b, l, f, c, s, p, pp)");
    }
  }
  if (!have_view) throw NffError(r.last(), "no view block: an NFF scene needs a 'v' line");
  // The SPD default intensity for lights without a colour: sqrt(n) / (2 n) each.
  float count = float(std::max<size_t>(s.lights.size(), 1));
  float intensity = std::sqrt(count) / (2.0f * count);
  for (size_t i = 0; i < s.lights.size(); ++i)
    if (!light_given[i]) s.lights[i].color = Rgb::gray(intensity);
  return s;
}
