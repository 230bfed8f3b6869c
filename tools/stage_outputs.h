// `relief stages`: every stage buffer of a frame as a picture and as raw floats.
//
// For each field a PNG people can look at and a PFM or EXR with the exact float values
// (float_image_file.h), plus stages.json: what each file holds, its units and value range, and
// the effective scene, which the PNG and EXR files carry too (image/image_metadata.h).
// Layout of the raw files: the grid's width x height vertices, row 0 = grid row j = 0 (the
// bottom of the projector image, nearest the camera), padding columns dropped.
#pragma once

#include <filesystem>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/scene/scene.h"
#include "tools/float_image_file.h"

namespace relief {

void write_stage_outputs(const std::filesystem::path& dir, const Scene& scene,
                         const FramePlan& plan, const GridBuffers<float>& buffers,
                         FloatFormat raw_format = FloatFormat::kPfm);

}  // namespace relief
