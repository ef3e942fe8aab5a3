// Label images (NIfTI, NRRD, MetaImage) read and written through ITK's ImageIO layer.
//
// ITK types stay in this file. We talk to itk::ImageIOBase directly (no itk::Image template), read
// the raw buffer in its on-disk component type and convert it to int32 labels with checks, so
// every pixel type costs one switch, not one template instantiation.
#include "contour4d/io/images.h"

#include <zlib.h>

#include <itkImageIOBase.h>
#include <itkImageIOFactory.h>
#include <itkMetaImageIOFactory.h>
#include <itkNiftiImageIOFactory.h>
#include <itkNrrdImageIOFactory.h>
#include <itkGDCMImageIOFactory.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string_view>
#include <sstream>
#include <limits>
#include <mutex>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxVoxels = std::size_t{1} << 28;  // 268 M voxels: far above any cine stack

Location at_file(const fs::path& p, int frame = -1) {
  Location l;
  l.file = p.string();
  l.frame = frame;
  return l;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Natural order: digit runs compare as numbers, so frame2 < frame10.
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t i2 = i, j2 = j;
      while (i2 < a.size() && std::isdigit(static_cast<unsigned char>(a[i2]))) ++i2;
      while (j2 < b.size() && std::isdigit(static_cast<unsigned char>(b[j2]))) ++j2;
      std::string na = a.substr(i, i2 - i), nb = b.substr(j, j2 - j);
      na.erase(0, std::min(na.find_first_not_of('0'), na.size()));
      nb.erase(0, std::min(nb.find_first_not_of('0'), nb.size()));
      if (na.size() != nb.size()) return na.size() < nb.size();
      if (na != nb) return na < nb;
      i = i2, j = j2;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
    }
  }
  if ((a.size() - i) != (b.size() - j)) return (a.size() - i) < (b.size() - j);
  return a < b;
}

// Shell-style match of a file name with '*' and '?'.
bool glob_match(const std::string& pat, const std::string& s) {
  std::size_t p = 0, i = 0, star = std::string::npos, mark = 0;
  while (i < s.size()) {
    if (p < pat.size() && (pat[p] == '?' || pat[p] == s[i])) {
      ++p, ++i;
    } else if (p < pat.size() && pat[p] == '*') {
      star = p++, mark = i;
    } else if (star != std::string::npos) {
      p = star + 1, i = ++mark;
    } else {
      return false;
    }
  }
  while (p < pat.size() && pat[p] == '*') ++p;
  return p == pat.size();
}

bool has_wildcard(const fs::path& p) { return p.filename().string().find_first_of("*?") != std::string::npos; }

void register_factories() {
  static std::once_flag once;
  std::call_once(once, [] {
    itk::NiftiImageIOFactory::RegisterOneFactory();
    itk::NrrdImageIOFactory::RegisterOneFactory();
    itk::MetaImageIOFactory::RegisterOneFactory();
    itk::GDCMImageIOFactory::RegisterOneFactory();
    itk::Object::GlobalWarningDisplayOff();
  });
}

// MetaImage and NRRD headers may name their data files with a printf pattern ("slice%03d.raw"). ITK's
// MetaIO passes the header's text to snprintf as the format, so a hostile header ("%s") crashes it
// (found by fuzz_images). Such patterns are refused before ITK reads the file.
void reject_data_file_patterns(const fs::path& file) {
  const std::string name = lower(file.filename().string());
  const bool meta = ends_with(name, ".mhd") || ends_with(name, ".mha");
  const bool nrrd = ends_with(name, ".nhdr") || ends_with(name, ".nrrd");
  if (!meta && !nrrd) return;
  std::ifstream in(file, std::ios::binary);
  std::string line;
  for (int n = 0; n < 200 && std::getline(in, line); ++n) {
    const std::size_t sep = line.find_first_of(meta ? "=" : ":");
    if (sep == std::string::npos) continue;
    const std::string key = lower(line.substr(0, sep));
    const bool hit = meta ? key.find("elementdatafile") != std::string::npos
                          : (key.find("data file") != std::string::npos || key.find("datafile") != std::string::npos);
    // Dimension fields: ITK's readers loop on them before checking (NDims = -3 hangs MetaIO).
    const bool dim_key = meta ? (key.find("ndims") != std::string::npos || key.find("dimsize") != std::string::npos)
                              : (key == "dimension" || key == "sizes");
    if (dim_key) {
      std::istringstream values(line.substr(sep + 1));
      std::string v;
      int count = 0;
      while (values >> v) {
        const bool digits = !v.empty() && v.size() <= 7 && v.find_first_not_of("0123456789") == std::string::npos;
        if (!digits || std::stol(v) < 1 || ++count > 5)
          throw IoError(ErrorCode::Format, at_file(file),
                        "invalid image dimensions in the header: '" + line.substr(0, 80) + "'",
                        "give a 3D or 4D label image with positive sizes");
      }
      if (count == 0)
        throw IoError(ErrorCode::Format, at_file(file), "empty image dimensions in the header",
                      "give a 3D or 4D label image");
      continue;
    }
    if (!hit) continue;
    if (line.find('%', sep) != std::string::npos)
      throw IoError(ErrorCode::Format, at_file(file),
                    "the header names its data files with a printf-style pattern ('%')",
                    "contour4d reads one data file per header: write the image as a single .mha, .nrrd or .nii.gz");
    return;  // the data follows this line in single-file formats
  }
}

// A header naming a data file beside it (.mhd ElementDataFile, .nhdr "data file") that is missing.
void check_companion(const fs::path& file) {
  const std::string name = lower(file.filename().string());
  const bool mhd = ends_with(name, ".mhd"), nhdr = ends_with(name, ".nhdr");
  if (!mhd && !nhdr) return;
  std::ifstream in(file);
  std::string line;
  for (int n = 0; n < 200 && std::getline(in, line); ++n) {
    const std::string key = lower(line.substr(0, line.find_first_of(mhd ? "=" : ":")));
    const bool hit = mhd ? key.find("elementdatafile") != std::string::npos
                         : (key.find("data file") != std::string::npos || key.find("datafile") != std::string::npos);
    if (!hit) continue;
    std::string value = line.substr(std::min(line.size(), line.find_first_of(mhd ? "=" : ":") + 1));
    value.erase(0, value.find_first_not_of(" \t"));
    while (!value.empty() && std::isspace(static_cast<unsigned char>(value.back()))) value.pop_back();
    if (value.empty() || value == "LOCAL" || value == "LIST" || value.rfind("LIST", 0) == 0 ||
        value.find_first_of(" %") != std::string::npos)
      return;
    const fs::path data = fs::path(value).is_absolute() ? fs::path(value) : file.parent_path() / value;
    if (!fs::exists(data))
      throw IoError(ErrorCode::MissingCompanion, at_file(file),
                    "data file '" + data.string() + "' named by the header is missing",
                    "put the data file beside the header, or give a single-file image (.nii.gz, .nrrd, .mha)");
    return;
  }
}

// zlib (and so ITK) accepts a .gz whose trailer is cut off; gzclose_r reports a stream that ended
// early, so a truncated file is an error rather than silently accepted.
void check_gzip_complete(const fs::path& file) {
  if (!ends_with(lower(file.filename().string()), ".gz")) return;
  gzFile gz = gzopen(file.string().c_str(), "rb");
  if (!gz) return;
  std::vector<char> scratch(1 << 16);
  int n = 0;
  while ((n = gzread(gz, scratch.data(), static_cast<unsigned>(scratch.size()))) > 0) {}
  const int close = gzclose_r(gz);
  if (n < 0 || close != Z_OK)
    throw IoError(ErrorCode::Parse, at_file(file), "the gzip stream is truncated or corrupt",
                  "the file was cut short (interrupted copy or download?); re-export it");
}

template <typename T>
void convert(const std::vector<char>& raw, std::vector<int32_t>& out, const fs::path& file) {
  const std::size_t n = raw.size() / sizeof(T);
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, raw.data() + i * sizeof(T), sizeof(T));
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(v))
        throw InvalidInput(ErrorCode::NonFinite, at_file(file), "the image holds a NaN or infinite value",
                           "give a label image (whole numbers)");
      if (v != std::round(v))
        throw InvalidInput(ErrorCode::Format, at_file(file),
                           "the image holds the non-integer value " + std::to_string(static_cast<double>(v)) +
                               ": it is not a label image",
                           "give a segmentation with integer labels (0 = background)");
    }
    if constexpr (std::is_floating_point_v<T> || sizeof(T) >= 4) {
      if (static_cast<long double>(v) > std::numeric_limits<int32_t>::max() ||
          static_cast<long double>(v) < std::numeric_limits<int32_t>::min())
        throw InvalidInput(ErrorCode::Format, at_file(file), "a label value is outside the 32-bit integer range",
                           "give a segmentation with small integer labels");
    }
    out[i] = static_cast<int32_t>(v);
  }
}

}  // namespace

bool is_label_image_file(const fs::path& path) {
  const std::string n = lower(path.filename().string());
  for (const char* e : {".nii", ".nii.gz", ".nrrd", ".nhdr", ".mha", ".mhd"})
    if (ends_with(n, e)) return true;
  return false;
}

bool is_label_image_input(const fs::path& input) {
  if (has_wildcard(input)) return true;
  std::error_code ec;
  if (fs::is_directory(input, ec)) {
    for (const auto& e : fs::directory_iterator(input, ec))
      if (e.is_regular_file(ec) && is_label_image_file(e.path())) return true;
    return false;
  }
  return is_label_image_file(input);
}

std::vector<fs::path> list_label_images(const fs::path& input) {
  std::vector<fs::path> files;
  std::error_code ec;
  if (has_wildcard(input)) {
    const fs::path dir = input.has_parent_path() ? input.parent_path() : fs::path(".");
    const std::string pat = input.filename().string();
    if (fs::is_directory(dir, ec))
      for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file(ec) && glob_match(pat, e.path().filename().string())) files.push_back(e.path());
  } else if (fs::is_directory(input, ec)) {
    std::vector<fs::path> all, gt;
    for (const auto& e : fs::directory_iterator(input, ec)) {
      if (!e.is_regular_file(ec) || !is_label_image_file(e.path())) continue;
      all.push_back(e.path());
      if (e.path().filename().string().find("_gt.") != std::string::npos) gt.push_back(e.path());
    }
    files = gt.empty() ? all : gt;
  } else if (fs::exists(input, ec)) {
    files.push_back(input);
  } else {
    throw IoError(ErrorCode::FileNotFound, at_file(input), "no such file or folder", "check the path");
  }
  if (files.empty())
    throw IoError(ErrorCode::FileNotFound, at_file(input),
                  "no label image (.nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd) matches",
                  "give a label image, a folder of them, or a pattern such as 'patient001_frame*_gt.nii.gz'");
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  return files;
}

// What a file is by its first bytes, when it is a common format that is no label image ("" otherwise).
std::string other_format(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(132, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  auto starts = [&head](std::string_view sig) { return head.compare(0, sig.size(), sig) == 0; };
  if (starts("\x89PNG")) return "a PNG image";
  if (starts("\xFF\xD8\xFF")) return "a JPEG image";
  if (starts("II*") || starts("MM"))
    return head.size() >= 4 && (head[2] == '*' || head[3] == '*') ? "a TIFF image" : "";
  if (starts("%PDF")) return "a PDF document";
  if (starts("PK\x03\x04")) return "a ZIP archive";
  if (head.size() >= 132 && head.compare(128, 4, "DICM") == 0) return "a DICOM file";
  return {};
}

std::vector<LabelVolume> read_label_image(const fs::path& file) {
  register_factories();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw IoError(ErrorCode::FileNotFound, at_file(file), "no such file", "check the path");
  if (fs::file_size(file, ec) == 0)
    throw IoError(ErrorCode::EmptyFile, at_file(file), "the file is empty", "give a label image");
  reject_data_file_patterns(file);
  check_companion(file);
  check_gzip_complete(file);
  itk::ImageIOBase::Pointer io =
      itk::ImageIOFactory::CreateImageIO(file.string().c_str(), itk::IOFileModeEnum::ReadMode);
  if (io.IsNull()) {
    if (const std::string what = other_format(file); !what.empty())
      throw InvalidInput(ErrorCode::Format, at_file(file),
                         "this is " + what + ", not a NIfTI, NRRD or MetaImage label image",
                         "give the label image itself (.nii, .nii.gz, .nrrd, .nhdr, .mha or .mhd); DICOM image folders "
                         "are read with their contours (Sunnybrook layout)");
    // A known extension whose header ITK cannot even recognise: truncated or corrupt.
    if (is_label_image_file(file))
      throw IoError(ErrorCode::Parse, at_file(file), "cannot read the image header",
                    "the file may be truncated or corrupt; re-export it");
    throw InvalidInput(ErrorCode::Format, at_file(file), "not a NIfTI, NRRD or MetaImage file",
                       "give a .nii, .nii.gz, .nrrd, .nhdr, .mha or .mhd label image");
  }
  std::vector<char> raw;
  std::vector<std::size_t> dims;
  try {
    io->SetFileName(file.string());
    io->ReadImageInformation();
    const unsigned nd = io->GetNumberOfDimensions();
    for (unsigned d = 0; d < nd; ++d) dims.push_back(io->GetDimensions(d));
    // Trailing axes of length 1 do not count (a 4D NIfTI with one time point is 3D).
    while (dims.size() > 3 && dims.back() == 1) dims.pop_back();
    if (dims.size() < 3)
      throw InvalidInput(ErrorCode::Format, at_file(file),
                         "the image is " + std::to_string(dims.size()) + "D; a label volume must be 3D or 3D+t",
                         "give the whole stack as one 3D image (or one 4D image), not single slices");
    if (dims.size() > 4)
      throw InvalidInput(ErrorCode::Format, at_file(file),
                         "the image has " + std::to_string(dims.size()) + " dimensions",
                         "give a 3D or 4D (3D+t) label image");
    if (io->GetPixelType() != itk::IOPixelEnum::SCALAR || io->GetNumberOfComponents() != 1)
      throw InvalidInput(ErrorCode::Format, at_file(file), "the image has vector or colour pixels",
                         "give a scalar label image");
    std::size_t voxels = 1;
    for (std::size_t d : dims) {
      if (d == 0 || voxels > kMaxVoxels / d)
        throw InvalidInput(ErrorCode::Format, at_file(file), "the image size is zero or too large",
                           "give a label image with at most 2^28 voxels");
      voxels *= d;
    }
    itk::ImageIORegion region(nd);
    for (unsigned d = 0; d < nd; ++d) {
      region.SetIndex(d, 0);
      region.SetSize(d, io->GetDimensions(d));
    }
    io->SetIORegion(region);
    const std::size_t bytes = voxels * io->GetComponentSize();
    raw.resize(bytes);
    io->Read(raw.data());
  } catch (const itk::ExceptionObject& e) {
    throw IoError(ErrorCode::Parse, at_file(file), std::string("cannot read the image: ") + e.GetDescription(),
                  "the file may be truncated or corrupt; re-export it");
  } catch (const std::bad_alloc&) {
    throw IoError(ErrorCode::Parse, at_file(file), "out of memory reading the image", "check the image header");
  }

  std::vector<int32_t> all;
  using C = itk::IOComponentEnum;
  switch (io->GetComponentType()) {
    case C::UCHAR:
      convert<unsigned char>(raw, all, file);
      break;
    case C::CHAR:
      convert<signed char>(raw, all, file);
      break;
    case C::USHORT:
      convert<uint16_t>(raw, all, file);
      break;
    case C::SHORT:
      convert<int16_t>(raw, all, file);
      break;
    case C::UINT:
      convert<uint32_t>(raw, all, file);
      break;
    case C::INT:
      convert<int32_t>(raw, all, file);
      break;
    case C::ULONG:
      convert<unsigned long>(raw, all, file);
      break;
    case C::LONG:
      convert<long>(raw, all, file);
      break;
    case C::ULONGLONG:
      convert<unsigned long long>(raw, all, file);
      break;
    case C::LONGLONG:
      convert<long long>(raw, all, file);
      break;
    case C::FLOAT:
      convert<float>(raw, all, file);
      break;
    case C::DOUBLE:
      convert<double>(raw, all, file);
      break;
    default:
      throw InvalidInput(ErrorCode::Format, at_file(file), "unsupported pixel type", "give an integer label image");
  }

  LabelVolume geo;
  for (int a = 0; a < 3; ++a) {
    const auto ua = static_cast<unsigned>(a);
    geo.dims[static_cast<std::size_t>(a)] = static_cast<int>(dims[static_cast<std::size_t>(a)]);
    geo.spacing[static_cast<std::size_t>(a)] = io->GetSpacing(ua);
    geo.origin[static_cast<std::size_t>(a)] = io->GetOrigin(ua);
    const std::vector<double> col = io->GetDirection(ua);
    for (int r = 0; r < 3; ++r)
      geo.direction[static_cast<std::size_t>(3 * r + a)] =
          r < static_cast<int>(col.size()) ? col[static_cast<std::size_t>(r)] : (r == a ? 1.0 : 0.0);
    if (!(geo.spacing[static_cast<std::size_t>(a)] > 0.0) || !std::isfinite(geo.spacing[static_cast<std::size_t>(a)]))
      throw InvalidInput(ErrorCode::Format, at_file(file), "voxel spacing must be positive and finite",
                         "fix the image header");
    if (!std::isfinite(geo.origin[static_cast<std::size_t>(a)]))
      throw InvalidInput(ErrorCode::NonFinite, at_file(file), "the image origin is not finite", "fix the image header");
  }
  for (double d : geo.direction)
    if (!std::isfinite(d))
      throw InvalidInput(ErrorCode::NonFinite, at_file(file), "the image direction is not finite",
                         "fix the image header");
  const std::size_t per = static_cast<std::size_t>(geo.dims[0]) * static_cast<std::size_t>(geo.dims[1]) *
                          static_cast<std::size_t>(geo.dims[2]);
  const std::size_t nt = dims.size() == 4 ? dims[3] : 1;
  std::vector<LabelVolume> out(nt, geo);
  for (std::size_t t = 0; t < nt; ++t)
    out[t].labels.assign(all.begin() + static_cast<std::ptrdiff_t>(t * per),
                         all.begin() + static_cast<std::ptrdiff_t>((t + 1) * per));
  return out;
}

LabelSeries read_label_series(const fs::path& input) {
  LabelSeries s;
  s.source = input.string();
  for (const fs::path& f : list_label_images(input)) {
    for (LabelVolume& v : read_label_image(f)) {
      s.frames.push_back(std::move(v));
      s.files.push_back(f.string());
    }
  }
  const LabelVolume& a = s.frames.front();
  for (std::size_t i = 1; i < s.frames.size(); ++i) {
    const LabelVolume& b = s.frames[i];
    const Location where = at_file(s.files[i], static_cast<int>(i));
    if (a.dims != b.dims)
      throw InvalidInput(ErrorCode::Format, where, "frame size differs from frame 0 (" + s.files[0] + ")",
                         "give frames of one acquisition, all with the same size");
    for (int k = 0; k < 3; ++k) {
      const auto uk = static_cast<std::size_t>(k);
      const double tol = 1e-4 * std::max(1.0, a.spacing[uk]);
      if (std::abs(a.spacing[uk] - b.spacing[uk]) > tol || std::abs(a.origin[uk] - b.origin[uk]) > 1e-3)
        throw InvalidInput(ErrorCode::Format, where,
                           "frame spacing or origin differs from frame 0 (" + s.files[0] + ")",
                           "give frames of one acquisition, all with the same geometry");
    }
    for (std::size_t k = 0; k < 9; ++k)
      if (std::abs(a.direction[k] - b.direction[k]) > 1e-4)
        throw InvalidInput(ErrorCode::NotParallel, where, "frame orientation differs from frame 0 (" + s.files[0] + ")",
                           "give frames of one acquisition, all with the same direction matrix");
  }
  s.times_ms.resize(s.frames.size());
  for (std::size_t i = 0; i < s.frames.size(); ++i) s.times_ms[i] = static_cast<double>(i);
  return s;
}

void write_label_volume(const fs::path& file, const std::vector<LabelVolume>& frames,
                        const ImageWriteOptions& options) {
  register_factories();
  if (frames.empty()) throw InvalidInput(ErrorCode::Format, at_file(file), "nothing to write");
  const LabelVolume& g = frames.front();
  const std::size_t per =
      static_cast<std::size_t>(g.dims[0]) * static_cast<std::size_t>(g.dims[1]) * static_cast<std::size_t>(g.dims[2]);
  for (const LabelVolume& v : frames)
    if (v.dims != g.dims || v.labels.size() != per)
      throw InvalidInput(ErrorCode::Format, at_file(file),
                         "frames of different sizes or labels.size() != dims product");
  if (options.two_d && (frames.size() != 1 || g.dims[2] != 1))
    throw InvalidInput(ErrorCode::Format, at_file(file), "a 2D image needs one frame with dims[2] == 1");
  itk::ImageIOBase::Pointer io =
      itk::ImageIOFactory::CreateImageIO(file.string().c_str(), itk::IOFileModeEnum::WriteMode);
  if (io.IsNull())
    throw InvalidInput(ErrorCode::Format, at_file(file), "no image writer for this extension",
                       "use .nii, .nii.gz, .nrrd or .mha");
  const unsigned nd = options.two_d ? 2u : (frames.size() > 1 ? 4u : 3u);
  io->SetNumberOfDimensions(nd);
  itk::ImageIORegion region(nd);
  for (unsigned d = 0; d < nd; ++d) {
    const std::size_t n = d < 3 ? static_cast<std::size_t>(g.dims[d]) : frames.size();
    io->SetDimensions(d, static_cast<itk::SizeValueType>(n));
    io->SetSpacing(d, d < 3 ? g.spacing[d] : 1.0);
    io->SetOrigin(d, d < 3 ? g.origin[d] : 0.0);
    std::vector<double> col(nd, 0.0);
    for (unsigned r = 0; r < nd; ++r) col[r] = (d < 3 && r < 3) ? g.direction[3 * r + d] : (r == d ? 1.0 : 0.0);
    io->SetDirection(d, col);
    region.SetIndex(d, 0);
    region.SetSize(d, n);
  }
  io->SetPixelType(itk::IOPixelEnum::SCALAR);
  io->SetNumberOfComponents(1);
  std::vector<char> buf;
  auto fill = [&](auto tag) {
    using T = decltype(tag);
    buf.resize(per * frames.size() * sizeof(T));
    std::size_t i = 0;
    for (const LabelVolume& v : frames)
      for (int32_t x : v.labels) {
        const T t = static_cast<T>(x * options.value_scale);
        std::memcpy(buf.data() + (i++) * sizeof(T), &t, sizeof(T));
      }
  };
  switch (options.pixel) {
    case ImagePixel::Int16:
      io->SetComponentType(itk::IOComponentEnum::SHORT);
      fill(int16_t{});
      break;
    case ImagePixel::Int32:
      io->SetComponentType(itk::IOComponentEnum::INT);
      fill(int32_t{});
      break;
    case ImagePixel::Float32:
      io->SetComponentType(itk::IOComponentEnum::FLOAT);
      fill(float{});
      break;
  }
  io->SetFileName(file.string());
  io->SetUseCompression(options.compress);
  io->SetIORegion(region);
  try {
    io->Write(buf.data());
  } catch (const itk::ExceptionObject& e) {
    throw IoError(ErrorCode::OutputNotWritable, at_file(file),
                  std::string("cannot write the image: ") + e.GetDescription(),
                  "check that the folder exists and is writable");
  }
}

}  // namespace c4d
