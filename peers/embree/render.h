// The render loop and the shading: rtprof's diffuse-only mode and its Whitted shading
// (tracer/src/shading.rs), on Embree's queries, one ray at a time or in packets.
#pragma once

#include <vector>

#include "camera.h"
#include "world.h"

enum class Shading { Color, Gray, DiffuseOnly };
// Single: rtcIntersect1 / rtcOccluded1 for every ray. Packets: rtcIntersect8 on 4×2
// pixel tiles, rtcOccluded8 for each light's shadow rays of a packet, secondary rays
// in packets of the lanes that spawn them (one lane left: a single ray).
enum class Mode { Single, Packets };

struct Options {
  int width = 0, height = 0, threads = 1, depth = 5;
  Mode mode = Mode::Packets;
  Shading shading = Shading::Color;
};

// Renders into `frame` (width × height pixels, zeroed, allocated by the caller so that
// its page faults fall outside the timed loop), row 0 at the top, in linear RGB (gray
// for Gray and DiffuseOnly).
void render(const World& world, const Camera& camera, const Options& options, std::vector<Rgb>& frame);
