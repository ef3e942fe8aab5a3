// The packing run (pack_run.h): resampling, compact encoding, model.c4d and glTF bytes.
#include "contour4d/pipeline/pack_run.h"

#include "contour4d/io/gltf.h"
#include "contour4d/temporal/model_c4d.h"
#include "contour4d/temporal/interpolate.h"

namespace c4d {

MeshSequence resample_if(MeshSequence seq, std::size_t frames, const std::string& interp) {
  if (frames == 0) return seq;
  const TimeInterpolation mode = interp == "linear" ? TimeInterpolation::Linear
                                 : interp == "step" ? TimeInterpolation::Step
                                                    : TimeInterpolation::CatmullRomPeriodic;
  return resample_sequence(seq, frames, mode);
}

PackRun pack_run(const MeshSequence& seq, const PackRunOptions& options) {
  PackRun run;
  run.input = resample_if(seq, options.resample, options.interp);
  CompactOptions opt;
  opt.tolerance = options.tolerance;
  opt.step = options.step;
  opt.normal_p99 = options.normal_p99;
  run.model = compact_encode(run.input, opt, nullptr, &run.stats);
  const ModelC4dWriteOptions write;  // zstd level 19 (model_c4d.h)
  run.c4d = serialize_model_c4d(run.model, write);
  // The zstd layer: the payload before compression (an uncompressed file less its header) against the stored one.
  ModelC4dWriteOptions raw_options = write;
  raw_options.compress = false;
  run.raw_payload = serialize_model_c4d(run.model, raw_options).size() - kModelC4dHeaderBytes;
  run.stored_payload = run.c4d.size() - kModelC4dHeaderBytes;
  if (options.gltf) {
    GltfOptions g;
    g.step = options.gltf_step;
    g.quantized = options.gltf_quantized;
    run.glb = gltf_glb_bytes(run.input, g);
  }
  return run;
}

}  // namespace c4d
