// rtprof-embree: a standalone ray tracer on Embree 3's API, written the way Embree's
// users write one, as the yardstick rtprof's peer runs set rtprof against. It reads
// the NFF file rtprof writes for outside tracers, draws it with rtprof's camera and
// shading (render.cpp), and prints its build and trace times.
//
//   rtprof-embree SCENE.nff [--size WxH] [--threads N] [--mode packets|single]
//                 [--diffuse-only | --gray | --shading color|gray|diffuse-only]
//                 [--depth N] [--robust] [-o IMAGE.ppm]
//
// Exit codes: 0 done, 1 Embree or the output failed, 2 bad input (arguments or scene).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "render.h"

namespace {

[[noreturn]] void usage(const std::string& message) {
  std::fprintf(stderr,
               "rtprof-embree: %s\n"
               "usage: rtprof-embree SCENE.nff [--size WxH] [--threads N] [--mode packets|single]\n"
               "                     [--diffuse-only | --gray | --shading color|gray|diffuse-only]\n"
               "                     [--depth N] [--robust] [-o IMAGE.ppm]\n",
               message.c_str());
  std::exit(2);
}

int positive(const std::string& option, const std::string& text, int most) {
  char* end = nullptr;
  long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < 1 || v > most)
    usage(option + " takes a whole number from 1 to " + std::to_string(most) + ", not '" + text + "'");
  return int(v);
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Binary PPM, each channel clamped to [0, 1], × 255 and rounded, as rtprof's to_rgb8.
bool write_ppm(const std::string& path, const std::vector<Rgb>& frame, int width, int height) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  std::fprintf(f, "P6\n%d %d\n255\n", width, height);
  std::vector<unsigned char> bytes;
  bytes.reserve(frame.size() * 3);
  auto q = [](float v) {
    if (!(v > 0)) return (unsigned char)0;  // NaN too, as Rust's `as u8`
    return (unsigned char)std::round(std::min(v, 1.0f) * 255.0f);
  };
  for (const Rgb& p : frame) bytes.insert(bytes.end(), {q(p.r), q(p.g), q(p.b)});
  bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  return std::fclose(f) == 0 && ok;
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path, output;
  Options o;
  bool robust = false;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "--size") {
      std::string v = value();
      auto x = v.find('x');
      if (x == std::string::npos) usage("--size takes WxH, e.g. 1024x1024, not '" + v + "'");
      o.width = positive("--size", v.substr(0, x), 16384);
      o.height = positive("--size", v.substr(x + 1), 16384);
    } else if (a == "--threads") {
      o.threads = positive(a, value(), 1024);
    } else if (a == "--depth") {
      o.depth = positive(a, value(), 64);
    } else if (a == "--mode") {
      std::string v = value();
      if (v == "packets") o.mode = Mode::Packets;
      else if (v == "single") o.mode = Mode::Single;
      else usage("--mode is packets or single, not '" + v + "'");
    } else if (a == "--robust") {
      robust = true;
    } else if (a == "--diffuse-only") {
      o.shading = Shading::DiffuseOnly;
    } else if (a == "--gray") {
      o.shading = Shading::Gray;
    } else if (a == "--shading") {
      std::string v = value();
      if (v == "color") o.shading = Shading::Color;
      else if (v == "gray") o.shading = Shading::Gray;
      else if (v == "diffuse-only") o.shading = Shading::DiffuseOnly;
      else usage("--shading is color, gray or diffuse-only, not '" + v + "'");
    } else if (a == "-o" || a == "--output") {
      output = value();
      if (!ends_with(output, ".ppm")) usage("the image is written as binary PPM: name it FILE.ppm");
    } else if (a == "-h" || a == "--help") {
      usage("a ray tracer on Embree 3, for rtprof's peer runs (peers/embree/README.md)");
    } else if (!a.empty() && a[0] == '-') {
      usage("unknown option " + a);
    } else if (scene_path.empty()) {
      scene_path = a;
    } else {
      usage("one scene only (" + scene_path + ", then " + a + ")");
    }
  }
  if (scene_path.empty()) usage("no scene given");

  Scene scene;
  try {
    scene = read_nff(scene_path);
  } catch (const NffError& e) {
    if (e.line > 0) std::fprintf(stderr, "rtprof-embree: %s:%d: %s\n", scene_path.c_str(), e.line, e.what());
    else std::fprintf(stderr, "rtprof-embree: %s: %s\n", scene_path.c_str(), e.what());
    return 2;
  }
  if (o.width == 0) o.width = scene.view.width, o.height = scene.view.height;

  auto start = std::chrono::steady_clock::now();
  World world(scene, o.threads, robust);
  double build = ms_since(start);
  Camera camera(scene.view, o.width, o.height);

  std::vector<Rgb> frame(size_t(o.width) * o.height);
  start = std::chrono::steady_clock::now();
  render(world, camera, o, frame);
  double trace = ms_since(start);

  std::printf("%s: %zu triangles, %zu spheres, %zu cones, %zu lights; %dx%d, %d thread%s, %s, %s\n",
              scene_path.c_str(), world.triangles(), scene.spheres.size(), scene.cones.size(),
              scene.lights.size(), o.width, o.height, o.threads, o.threads == 1 ? "" : "s",
              o.mode == Mode::Packets ? "packets (rtcIntersect8, 4x2 tiles)" : "single rays (rtcIntersect1)",
              o.shading == Shading::DiffuseOnly ? "diffuse-only"
              : o.shading == Shading::Gray      ? ("gray, depth " + std::to_string(o.depth)).c_str()
                                                : ("colour, depth " + std::to_string(o.depth)).c_str());
  if (world.flat.self_intersecting + world.smooth.self_intersecting > 0)
    std::fprintf(stderr, "rtprof-embree: %d self-intersecting outline(s) drawn as fans from vertex 0\n",
                 world.flat.self_intersecting + world.smooth.self_intersecting);
  // Build: parse excluded, triangulation and rtcCommitScene included. Trace: the render
  // loop only (camera rays, queries, shading), as rtprof's own "tracing" figure.
  std::printf("build: %.3f ms\n", build);
  std::printf("trace: %.3f ms\n", trace);
  if (!output.empty() && !write_ppm(output, frame, o.width, o.height)) {
    std::fprintf(stderr, "rtprof-embree: cannot write %s\n", output.c_str());
    return 1;
  }
  return 0;
}
