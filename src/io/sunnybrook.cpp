// Contours drawn on DICOM images (Sunnybrook Cardiac Data layout): pixel coordinates -> patient
// space through each image's ImagePositionPatient, ImageOrientationPatient and PixelSpacing.
//
// Reference: Radau et al., "Evaluation Framework for Algorithms Segmenting Short Axis Cardiac
// MRI", MIDAS Journal 2009 (the data set and its file layout); DICOM PS3.3 C.7.6.2 (Image Plane
// Module: the pixel -> patient mapping). The tags are read with ITK's GDCMImageIO.
#include "contour4d/io/sunnybrook.h"

#include <itkGDCMImageIO.h>
#include <itkMetaDataObject.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <cstdio>
#include <map>
#include <mutex>
#include <regex>
#include <sstream>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

namespace fs = std::filesystem;

struct ContourFile {
  fs::path path;
  std::string series;  // "0001"
  int number = 0;      // NNNN: the image's InstanceNumber
  bool inner = true;   // i-contour (endocardium) or o-contour (epicardium)
};

struct DicomInfo {
  Vec3 ipp, x, y;         // position, row and column direction cosines
  double dr = 1, dc = 1;  // row spacing, column spacing (mm)
  int instance = -1;
  int phases = 20;       // CardiacNumberOfImages
  double trigger = NAN;  // ms
};

Location at(const fs::path& p, int line = -1) {
  Location l;
  l.file = p.string();
  l.line = line;
  return l;
}

std::vector<ContourFile> list_contours(const fs::path& folder, const char* sub, bool inner) {
  std::vector<ContourFile> out;
  const fs::path dir = folder / sub;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  static const std::regex name(R"(IM-(\d+)-(\d+)-([io])contour-manual\.txt)");
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    std::smatch m;
    const std::string fn = e.path().filename().string();
    if (!e.is_regular_file(ec) || !std::regex_match(fn, m, name)) continue;
    ContourFile c;
    c.path = e.path();
    c.series = m[1].str();
    c.number = std::stoi(m[2].str());
    c.inner = inner;
    out.push_back(c);
  }
  std::sort(out.begin(), out.end(), [](const ContourFile& a, const ContourFile& b) { return a.number < b.number; });
  return out;
}

std::vector<double> parse_ds(const std::string& s) {
  std::vector<double> v;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, '\\')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
    } catch (const std::exception&) {
      return {};
    }
  }
  return v;
}

DicomInfo read_dicom(const fs::path& file) {
  static std::once_flag once;
  std::call_once(once, [] { itk::Object::GlobalWarningDisplayOff(); });
  itk::GDCMImageIO::Pointer io = itk::GDCMImageIO::New();
  try {
    if (!io->CanReadFile(file.string().c_str()))
      throw IoError(ErrorCode::Parse, at(file), "not a readable DICOM file",
                    "give the DICOM image the contour was drawn on");
    io->SetFileName(file.string());
    io->ReadImageInformation();
  } catch (const itk::ExceptionObject& e) {
    throw IoError(ErrorCode::Parse, at(file), std::string("cannot read the DICOM header: ") + e.GetDescription(),
                  "the file may be truncated or corrupt");
  }
  const itk::MetaDataDictionary& dict = io->GetMetaDataDictionary();
  auto tag = [&](const char* key) {
    std::string v;
    itk::ExposeMetaData<std::string>(dict, key, v);
    return v;
  };
  auto need = [&](const char* key, const char* name, std::size_t n) {
    const std::vector<double> v = parse_ds(tag(key));
    if (v.size() != n)
      throw InvalidInput(ErrorCode::Format, at(file),
                         std::string("the DICOM image lacks a valid ") + name + " (" + key + ")",
                         "contours need the image's geometry: give the original DICOM file");
    for (double d : v)
      if (!std::isfinite(d))
        throw InvalidInput(ErrorCode::NonFinite, at(file), std::string(name) + " is not finite",
                           "fix the DICOM header");
    return v;
  };
  DicomInfo d;
  const auto ipp = need("0020|0032", "ImagePositionPatient", 3);
  const auto iop = need("0020|0037", "ImageOrientationPatient", 6);
  const auto ps = need("0028|0030", "PixelSpacing", 2);
  d.ipp = {ipp[0], ipp[1], ipp[2]};
  d.x = {iop[0], iop[1], iop[2]};
  d.y = {iop[3], iop[4], iop[5]};
  d.dr = ps[0];
  d.dc = ps[1];
  if (!(d.dr > 0 && d.dc > 0) || std::abs(norm(d.x) - 1) > 1e-3 || std::abs(norm(d.y) - 1) > 1e-3)
    throw InvalidInput(ErrorCode::Format, at(file), "PixelSpacing or ImageOrientationPatient is invalid",
                       "fix the DICOM header");
  if (auto v = parse_ds(tag("0020|0013")); v.size() == 1) d.instance = static_cast<int>(std::lround(v[0]));
  if (auto v = parse_ds(tag("0018|1090")); v.size() == 1 && v[0] >= 1) d.phases = static_cast<int>(std::lround(v[0]));
  if (auto v = parse_ds(tag("0018|1060")); v.size() == 1 && std::isfinite(v[0])) d.trigger = v[0];
  return d;
}

fs::path find_dicom(const fs::path& folder, const ContourFile& c) {
  char four[16];
  std::snprintf(four, sizeof four, "%04d", c.number);
  for (const fs::path& dir : {folder / "dicoms_contoured", folder / "dicoms", folder})
    for (const std::string& name : {std::to_string(c.number) + ".dcm", "IM-" + c.series + "-" + four + ".dcm"}) {
      std::error_code ec;
      if (fs::is_regular_file(dir / name, ec)) return dir / name;
    }
  throw IoError(ErrorCode::MissingCompanion, at(c.path),
                "the DICOM image " + std::to_string(c.number) + " this contour was drawn on is missing",
                "put " + std::to_string(c.number) + ".dcm (or IM-" + c.series + "-" + four +
                    ".dcm) in dicoms_contoured/ beside the contour folders");
}

std::vector<Vec2> read_points(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw IoError(ErrorCode::FileNotFound, at(file), "cannot open the contour file", "check permissions");
  std::vector<Vec2> pts;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream ls(line);
    double x = 0, y = 0;
    std::string rest;
    if (!(ls >> x >> y) || (ls >> rest))
      throw IoError(ErrorCode::Parse, at(file, n), "expected two numbers 'x y' (pixel column and row)",
                    "each line of a Sunnybrook contour file holds one point");
    if (!std::isfinite(x) || !std::isfinite(y))
      throw InvalidInput(ErrorCode::NonFinite, at(file, n), "non-finite coordinate", "fix the contour file");
    const Vec2 p{x, y};
    if (pts.empty() || !(pts.back() == p)) pts.push_back(p);
  }
  while (pts.size() > 1 && pts.back() == pts.front()) pts.pop_back();
  if (pts.empty())
    throw IoError(ErrorCode::EmptyFile, at(file), "the contour file has no points", "remove it or redraw the contour");
  return pts;
}

}  // namespace

bool is_sunnybrook_folder(const fs::path& folder) {
  return !list_contours(folder, "i-contours", true).empty() || !list_contours(folder, "o-contours", false).empty();
}

InputResult read_sunnybrook(const fs::path& folder, const SunnybrookOptions& options) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw IoError(ErrorCode::FileNotFound, at(folder), "no such folder", "give a Sunnybrook patient folder");
  if (options.space != "LPS" && options.space != "RAS")
    throw InvalidInput(ErrorCode::Usage, at(folder), "unknown space '" + options.space + "'", "use LPS or RAS");
  std::vector<ContourFile> files;
  if (options.contours != SunnybrookContours::Epicardium) files = list_contours(folder, "i-contours", true);
  if (options.contours != SunnybrookContours::Endocardium) {
    auto o = list_contours(folder, "o-contours", false);
    files.insert(files.end(), o.begin(), o.end());
  }
  if (files.empty())
    throw IoError(ErrorCode::FileNotFound, at(folder),
                  std::string("no ") +
                      (options.contours == SunnybrookContours::Epicardium ? "o-contours/" : "i-contours/") +
                      "IM-*-NNNN-*contour-manual.txt files",
                  "give a Sunnybrook patient folder (i-contours/, o-contours/, dicoms_contoured/)");

  struct Item {
    ContourFile file;
    DicomInfo dicom;
    int phase = 0, slice = 0;
  };
  std::vector<Item> items;
  std::map<int, std::vector<double>> triggers;  // phase -> trigger times of its images
  std::map<int, DicomInfo> cache;
  for (const ContourFile& c : files) {
    Item it;
    it.file = c;
    auto hit = cache.find(c.number);
    if (hit == cache.end()) {
      const fs::path dcm = find_dicom(folder, c);
      hit = cache.emplace(c.number, read_dicom(dcm)).first;
      if (hit->second.instance >= 0 && hit->second.instance != c.number)
        throw InvalidInput(ErrorCode::Format, at(dcm),
                           "InstanceNumber " + std::to_string(hit->second.instance) +
                               " differs from the contour file's image number " + std::to_string(c.number),
                           "pair each contour file with the DICOM image it names");
      triggers[(c.number - 1) % hit->second.phases].push_back(hit->second.trigger);
    }
    it.dicom = hit->second;
    it.phase = (c.number - 1) % it.dicom.phases;
    it.slice = (c.number - 1) / it.dicom.phases;
    items.push_back(it);
  }
  std::map<int, int> frame_of;  // phase -> frame index, phases in order
  for (const Item& it : items) frame_of.emplace(it.phase, 0);
  int nf = 0;
  for (auto& [phase, f] : frame_of) f = nf++;
  std::vector<double> times;
  bool timed = true;
  for (const auto& [phase, f] : frame_of) {
    double sum = 0;
    for (double t : triggers[phase]) {
      timed = timed && std::isfinite(t);
      sum += t;
    }
    times.push_back(sum / static_cast<double>(std::max<std::size_t>(1, triggers[phase].size())));
  }
  if (!timed)
    for (const auto& [phase, f] : frame_of) times[static_cast<std::size_t>(f)] = phase;

  std::vector<RawContour> raw;
  std::vector<int> index(static_cast<std::size_t>(nf), 0);
  double pixel_sum = 0.0;
  for (const Item& it : items) {
    const std::vector<Vec2> px = read_points(it.file.path);
    RawContour rc;
    rc.frame = frame_of[it.phase];
    rc.index = index[static_cast<std::size_t>(rc.frame)]++;
    rc.line = 1;
    rc.contour.label = it.file.inner ? "lv-endo" : "lv-epi";
    rc.contour.slice = it.slice;
    const DicomInfo& d = it.dicom;
    pixel_sum += 0.5 * (d.dr + d.dc);
    for (const Vec2& q : px) {
      Vec3 p = d.ipp + (q.x * d.dc) * d.x + (q.y * d.dr) * d.y;
      if (options.space == "RAS") p = {-p.x, -p.y, p.z};
      rc.contour.points.push_back(p);
    }
    raw.push_back(std::move(rc));
  }
  InputResult r;
  r.sequence = build_sequence(raw, nf, times, folder.string(), options.stack);
  r.sequence.space = options.space;
  r.format = "sunnybrook";
  r.pixel_mm = items.empty() ? 0.0 : pixel_sum / static_cast<double>(items.size());
  std::string phases;
  for (const auto& [phase, f] : frame_of) phases += (phases.empty() ? "" : ", ") + std::to_string(phase);
  r.notes.push_back(std::to_string(items.size()) + " contour files on " + std::to_string(cache.size()) +
                    " DICOM images; phases " + phases + " -> " + std::to_string(nf) + " frame(s)");
  r.notes.push_back(std::string("frame times from ") +
                    (timed ? "TriggerTime (0018,1060)" : "the phase index (1 ms per phase)"));
  r.notes.push_back("coordinates: " + options.space + " mm (DICOM patient space" +
                    (options.space == "RAS" ? ", x and y negated)" : ")"));
  return r;
}

}  // namespace c4d
