#pragma once
//! \file evaluation.h
//! \brief All the papers' measures for a 4D mesh, per frame and summarised: topology, triangle
//! quality, conformity to the contours, accuracy against a ground truth, volumes and EF, and
//! vertex correspondence (Lim et al. 2014, "Experimental Setup"; Tables 3–5, Figure 10).

#include <optional>
#include <string>
#include <vector>

#include "contour4d/core/stack.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/metrics/normal_deviation.h"
#include "contour4d/metrics/conformity.h"
#include "contour4d/metrics/correspondence.h"
#include "contour4d/metrics/crease.h"
#include "contour4d/metrics/distance.h"
#include "contour4d/metrics/quality.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/metrics/volume.h"

namespace c4d {

//! Options of evaluate.
struct EvaluationOptions {
  ConformityOptions conformity;          //!< contour sampling (0.2 mm)
  AngleQualityOptions quality;           //!< bad-angle threshold (25°)
  TopologyOptions topology;              //!< whether to test self-intersections
  CorrespondenceOptions correspondence;  //!< shuffled-vertex thresholds
  SurfaceSamplingOptions sampling;       //!< sample placement for accuracy against the truth
};

//! The measures of one frame; optional parts are absent when their input was not given.
struct FrameEvaluation {
  int frame = 0;                                   //!< 0-based frame index
  double time_ms = 0.0;                            //!< frame time (ms)
  TopologyReport topology;                         //!< validity of the surface
  AngleQuality quality;                            //!< Tables 3 and 4
  double volume = 0.0;                             //!< signed volume of the mesh (mm³)
  std::optional<DistanceStats> conformity;         //!< contours → mesh (mm), when contours are given
  std::optional<CreaseAngles> creases;             //!< angles on the contour lines and between, when contours are given
  std::optional<DiscVolume> simpson;               //!< disc volume of the frame's contours, when given
  std::optional<SurfaceComparison> accuracy;       //!< mesh ↔ truth (mm), when a truth is given
  std::optional<DistanceStats> contours_to_truth;  //!< contours → truth (mm): Table 5's reference column
  std::optional<NormalDeviation> normals;          //!< facet normals against the truth's (degrees), when given
};

//! The whole evaluation.
struct Evaluation {
  std::vector<FrameEvaluation> frames;         //!< one per mesh frame, in order
  CorrespondenceReport correspondence;         //!< across frames
  EjectionFraction mesh_ef;                    //!< from the mesh volumes
  std::optional<EjectionFraction> simpson_ef;  //!< from the disc volumes, when contours are given
  std::vector<std::string> faults;             //!< every fault, prefixed with its frame ("frame 3: ...")
  std::vector<std::string> notes;              //!< remarks that are not faults (frame count mismatches, ...)
  double conformity_step = 0.2;                //!< contour sampling interval used (mm)

  //! A frame has a topology fault or the vertex correspondence is broken (what `--check` tests).
  bool has_topology_fault() const;
};

//! Measures every frame of `meshes` (in parallel over frames; the result does not depend on the
//! thread count). Frame i of `contours` and of `truth` is compared with frame i of `meshes`;
//! frames missing on one side are skipped with a note.
//! \param contours the input contours, or nullptr
//! \param truth per-frame ground-truth meshes, or nullptr
Evaluation evaluate(const MeshFrames& meshes, const Sequence* contours, const MeshFrames* truth,
                    const EvaluationOptions& options = {});

//! The evaluation as JSON ("format": "contour4d-evaluation"), units named in the keys and in a
//! "units" object. Deterministic: same evaluation, same bytes.
std::string format_evaluation_json(const Evaluation& evaluation);

//! A human summary: one table row per frame, the summary lines (Tables 3–5, EF) and every fault.
std::string format_evaluation_table(const Evaluation& evaluation);

}  // namespace c4d
