// Case-file keys of the checkpoint section (see docs/checkpoint.md).
#include <limits>

#include "sim/keys/effect_doc.hpp"

namespace grains::io {

void register_checkpoint_docs() {
  using K = sim::KeyType;
  const double inf = std::numeric_limits<double>::infinity();
  sim::register_effect_doc(
      {"checkpoint", "checkpoint: {...}",
       "HDF5 checkpoints of the full state in OUTDIR/checkpoints/checkpoint_<step>.h5, written atomically "
       "(temporary file, fsync, rename); continue a run with grains run CASE --restart FILE or --resume OUTDIR. "
       "Without every/every_steps a checkpoint is written only on SIGINT/SIGTERM (and after an output failure); "
       "with them also at the end of the run.",
       {sim::key("every", K::Number, "simulated time between checkpoints").si("s").in(0, inf, true),
        sim::key("every_steps", K::Integer, "steps between checkpoints (instead of every)").in(1, 1e15),
        sim::key("keep", K::Integer, "how many of the newest checkpoints to keep").def("3").in(1, 1e6)}});
}

}  // namespace grains::io
