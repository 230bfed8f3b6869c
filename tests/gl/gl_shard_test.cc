// GL renders in shards (tools/shard.h): the GL backend draws whole frames and keeps the
// shard's rows (render_frame_rows), so the stitched image is the one-process GL render's bytes.
#include <catch2/catch.hpp>

#include "tests/support/shard_support.h"

namespace relief {
namespace {

using test::require_stitched_equal;

// GL draws whole frames and keeps the shard's rows (render_frame_rows).
TEST_CASE("glShardsStitchToTheBytesOfOneGlRender", "[gl]") {
  require_stitched_equal("default", 157, 200, 3, {"--backend", "gl"});
  require_stitched_equal("planet", 157, 200, 2, {"--backend", "gl"});
}

}  // namespace
}  // namespace relief
