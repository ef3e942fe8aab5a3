#pragma once
//! \file images.h
//! \brief Label images (NIfTI, NRRD, MetaImage; 3D or 3D+t) read with ITK into plain volumes.
//!
//! World geometry is kept exactly as ITK reports it: LPS millimetres, from the image's origin,
//! spacing and direction (NIfTI sform/qform converted by ITK). No ITK type appears here.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace c4d {

//! One 3D label image (one time frame). Voxel (i, j, k) lies at world point
//! origin + D · (i·spacing[0], j·spacing[1], k·spacing[2]) (LPS mm), D the direction matrix.
struct LabelVolume {
  std::array<int, 3> dims{0, 0, 0};        //!< voxels along i, j, k
  std::array<double, 3> spacing{1, 1, 1};  //!< voxel size along i, j, k (mm)
  std::array<double, 3> origin{0, 0, 0};   //!< world position of voxel (0, 0, 0) (LPS mm)
  std::array<double, 9> direction{1, 0, 0, 0, 1,
                                  0, 0, 0, 1};  //!< row-major 3×3; column a is the world direction of axis a
  std::vector<int32_t> labels;  //!< dims[0]·dims[1]·dims[2] values, i fastest: labels[i + dims[0]·(j + dims[1]·k)]
};

//! The frames of a label series, in time order, with one geometry.
struct LabelSeries {
  std::vector<LabelVolume> frames;  //!< one volume per time frame, same dims and geometry
  std::vector<double> times_ms;     //!< per frame; frame index × 1 ms (label images carry no reliable timing)
  std::vector<std::string> files;   //!< the file each frame came from (a 4D file repeats)
  std::string source;               //!< the INPUT as given (for messages)
};

//! True when `path` names a label image by its extension (.nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd).
bool is_label_image_file(const std::filesystem::path& path);

//! True when `input` is a label image file, a folder holding label images, or a file-name pattern
//! with '*' / '?' matching label images (e.g. "patient001/patient001_frame*_gt.nii.gz").
bool is_label_image_input(const std::filesystem::path& input);

//! The files of a label-image INPUT, one per frame, in natural name order (frame2 before frame10):
//! a single file; a pattern with '*' / '?' in the file name; or a folder — its *_gt.* files when it
//! has any (ACDC keeps images beside ground truth), else every label image in it.
//! \throw IoError (FileNotFound) when nothing matches.
std::vector<std::filesystem::path> list_label_images(const std::filesystem::path& input);

//! Reads one label image: 3D, or 4D (3D+t, one volume per time point). Integer pixel types, or
//! floating point whose values are all whole numbers.
//! \throw IoError (FileNotFound, Parse for a truncated or unreadable file, MissingCompanion for a
//! missing .raw beside a header) / InvalidInput (Format: not 3D/4D, vector pixels, non-integer
//! or out-of-range values, NonFinite).
std::vector<LabelVolume> read_label_image(const std::filesystem::path& file);

//! Reads every file of list_label_images(input) (each 3D, or one 4D file) into one series and
//! checks that all frames share dims, spacing, origin and direction.
//! \throw as read_label_image; InvalidInput (Format: different dims/spacing/origin,
//! NotParallel: different direction) naming the frame.
LabelSeries read_label_series(const std::filesystem::path& input);

//! Pixel type written by write_label_volume.
enum class ImagePixel { Int16, Int32, Float32 };

//! How write_label_volume writes (a helper for tests and demos).
struct ImageWriteOptions {
  ImagePixel pixel = ImagePixel::Int16;  //!< component type on disk
  double value_scale = 1.0;  //!< value written = label × value_scale (tests write non-integer images this way)
  bool two_d = false;        //!< write a 2D image (needs dims[2] == 1; tests of bad input)
  bool compress = true;      //!< compress when the format can (.nii.gz is always compressed)
};

//! Writes one volume (3D) or several (one 4D file, frames along t) with ITK; the format follows
//! the extension. \throw IoError (OutputNotWritable) / InvalidInput (Format) for bad volumes.
void write_label_volume(const std::filesystem::path& file, const std::vector<LabelVolume>& frames,
                        const ImageWriteOptions& options = {});

}  // namespace c4d
