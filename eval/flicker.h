// Flicker as a measured error (relief flicker; docs/ground-truth.md, "Flicker"): a short camera
// move rendered frame by frame in real time and as ground truth, and how much each changes from
// one frame to the next per band of distance (sky; near, middle and far thirds of the terrain,
// convergence.h). The truth's change is what the scene's own motion changes; a real-time frame
// that changes more flickers (popping geometry, crawling edges, sparkling layers).
#pragma once

#include <string_view>
#include <vector>

#include "core/scene/scene.h"
#include "eval/convergence.h"

namespace relief {

enum class CameraMove { kForward, kTurn };

std::string_view camera_move_name(CameraMove move);  // "forward", "turn"

// Frame k of the move: the camera `k * step` world units further along its horizontal forward
// direction (forward), or turned `k * step` degrees of yaw (turn).
Scene moved_scene(const Scene& scene, CameraMove move, double step, int k);

struct FlickerFrame {
  BandedError error;             // the real-time frame against its truth
  std::vector<double> realtime;  // banded_change from the previous frame (empty for frame 0)
  std::vector<double> truth;
};

struct FlickerReport {
  std::vector<FlickerFrame> frames;
  // Means over frames 1 ... F - 1 (per band, then all: kDistanceBands + 1 values), and the mean
  // FLIP of every frame against its truth per band, each over the frames where the band has
  // pixels; `*_frames` count them (0: the band was empty throughout, and its means say nothing).
  std::vector<double> realtime_change, truth_change, mean_flip;
  std::vector<std::size_t> change_frames, flip_frames;
};

// The means of `frames` (each with its changes but frame 0).
FlickerReport summarise_flicker(std::vector<FlickerFrame> frames);

}  // namespace relief
