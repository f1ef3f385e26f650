// rtprof's camera (tracer/src/camera.rs, pixel centres, as `rtprof render` samples by
// default): w = normalize(at - from), u = normalize(w × up), v = u × w; square samples
// whose pitch makes the angle span from the centre of the top row to the centre of the
// bottom one; the ray through sample (x, y) is normalize((w + y·v·pitch) + x·u·pitch),
// summed in that order, with x, y the sample's offsets from the grid's centre.
#pragma once

#include <algorithm>
#include <cmath>

#include "nff.h"

struct Camera {
  Vec3 eye, forward, right, up;
  int columns, rows;

  Camera(const View& view, int width, int height) : eye(view.from), columns(width), rows(height) {
    Vec3 w = normalize(view.at - view.from);
    Vec3 u = normalize(cross(w, view.up));
    Vec3 v = cross(u, w);
    // f32 as rtprof: angle_deg.to_radians() (× PI/180 in f32), halved, tan.
    const float rads_per_deg = float(M_PI) / 180.0f;
    float half_span = std::tan(view.angle_deg * rads_per_deg * 0.5f);
    float pitch = 2.0f * half_span / float(std::max(rows, 2) - 1);
    forward = w;
    right = u * pitch;
    up = v * pitch;
  }

  Vec3 direction(int column, int row) const {
    float x = float(column) - float(columns - 1) * 0.5f;
    float y = float(rows - 1) * 0.5f - float(row);
    Vec3 d = forward + up * y;
    d = d + right * x;
    return normalize(d);
  }
};
