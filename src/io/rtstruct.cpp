// DICOM RT structure sets (RTSTRUCT): each ROI's closed planar contours, already in patient space (mm), become
// one labelled set of contours of one frame, grouped into slices by their plane.
//
// Reference: DICOM PS3.3 A.19 (RT Structure Set IOD), C.8.8.5 (Structure Set Module: StructureSetROISequence,
// ReferencedFrameOfReferenceSequence), C.8.8.6 (ROI Contour Module: ContourSequence, ContourGeometricType,
// ContourData as x\y\z triplets in the patient coordinate system), C.8.8.8 (RT ROI Observations Module).
// The file is parsed by DCMTK's dcmdata and its sequences read through DCMTK's dcmrt classes.
#include "contour4d/io/rtstruct.h"

#include <dcmtk/config/osconfig.h>  // DCMTK wants its configuration first
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmdata/dcxfer.h>
#include <dcmtk/dcmrt/seq/drtcs.h>
#include <dcmtk/dcmrt/seq/drtrcs.h>
#include <dcmtk/dcmrt/seq/drtrfors.h>
#include <dcmtk/dcmrt/seq/drtrros.h>
#include <dcmtk/dcmrt/seq/drtrses.h>
#include <dcmtk/dcmrt/seq/drtrsts.h>
#include <dcmtk/dcmrt/seq/drtssrs.h>
#include <dcmtk/oflog/oflog.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string_view>

#include <fmt/format.h>

#include "contour4d/core/contour_repair.h"
#include "contour4d/core/errors.h"

namespace c4d {
namespace {

namespace fs = std::filesystem;

// One contour of an ROI as the file gives it.
struct RoiContour {
  std::vector<Vec3> points;  // mm, LPS
  int item = 0;              // 0-based index in the ROI's ContourSequence
};

// One ROI: StructureSetROISequence, its ROIContourSequence item and its observation.
struct Roi {
  int number = 0;
  std::string name, label, frame_of_reference, interpreted_type;
  std::vector<RoiContour> contours;     // CLOSED_PLANAR (and CLOSED_PLANAR_XOR) contours
  std::map<std::string, int> left_out;  // other geometric types -> how many
  bool has_contour_sequence = false;
};

// ReferencedFrameOfReferenceSequence: the frames of reference listed and the series under them.
struct References {
  bool present = false;
  std::set<std::string> frames_of_reference;
  std::vector<std::pair<std::string, std::size_t>> series;  // SeriesInstanceUID, ContourImageSequence items
};

Location at(const fs::path& file, const std::string& part = {}, int contour = -1) {
  Location l;
  l.file = file.string();
  l.part = part;
  l.contour = contour;
  return l;
}

std::string roi_part(const Roi& r) { return fmt::format("ROI {} \"{}\"", r.number, r.name); }

std::string trim(std::string s) {
  const auto not_space = [](unsigned char c) { return !std::isspace(c) && c != '\0'; };
  s.erase(s.begin(), std::find_if(s.begin(), s.end(), not_space));
  s.erase(std::find_if(s.rbegin(), s.rend(), not_space).base(), s.end());
  return s;
}

template <class Get>
std::string text(Get&& get) {
  OFString v;
  return get(v).good() ? trim(v.c_str()) : std::string();
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// DCMTK logs through oflog (warnings on stderr by default); our errors carry the context instead.
void quiet_dcmtk() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const char* name : {"dcmtk.dcmdata", "dcmtk.dcmrt"})
      OFLog::getLogger(name).setLogLevel(OFLogger::OFF_LOG_LEVEL);
  });
}

// "CTImageStorage" -> "CT Image Storage".
std::string words(const std::string& camel) {
  std::string out;
  for (std::size_t i = 0; i < camel.size(); ++i) {
    const auto up = [&](std::size_t k) {
      return k < camel.size() && std::isupper(static_cast<unsigned char>(camel[k]));
    };
    if (i > 0 && up(i) && (!up(i - 1) || (i + 1 < camel.size() && !up(i + 1) && up(i - 1)))) out += ' ';
    out += camel[i];
  }
  return out;
}

// Step 1: the file, parsed (values over 4 kB are read on access).
std::unique_ptr<DcmFileFormat> load(const fs::path& file) {
  quiet_dcmtk();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw IoError(ErrorCode::FileNotFound, at(file), "no such file", "give the RT structure set's .dcm file");
  if (fs::file_size(file, ec) == 0)
    throw IoError(ErrorCode::EmptyFile, at(file), "the file is empty", "give the RT structure set's .dcm file");
  auto ff = std::make_unique<DcmFileFormat>();
  const OFCondition c =
      ff->loadFile(OFFilename(file.c_str()), EXS_Unknown, EGL_noChange, DCM_MaxReadLength, ERM_autoDetect);
  if (c.bad())
    throw IoError(ErrorCode::Parse, at(file), std::string("not readable as DICOM: ") + c.text(),
                  "the file may be truncated or corrupt");
  return ff;
}

// Bytes an element takes in the file by its declared length (header included).
std::uint64_t extent(DcmObject& e, bool explicit_vr) {
  const bool long_header = explicit_vr && DcmVR(e.getVR()).usesExtendedLengthEncoding();
  return (long_header ? 12u : 8u) + static_cast<std::uint64_t>(e.getLengthField());
}

// Whether a sequence of defined length, and down its last items, holds the bytes it declares. DCMTK accepts a
// file that ends between two items or two elements of one (an undefined length needs its delimitation item,
// which DCMTK checks). Items of undefined length cannot be summed: taken as whole.
bool holds_declared(DcmSequenceOfItems& sq, bool explicit_vr) {
  if (sq.getLengthField() == DCM_UndefinedLength) return true;
  std::uint64_t items = 0;
  for (unsigned long i = 0; i < sq.card(); ++i) {
    if (sq.getItem(i)->getLengthField() == DCM_UndefinedLength) return true;
    items += 8 + static_cast<std::uint64_t>(sq.getItem(i)->getLengthField());
  }
  if (items < sq.getLengthField()) return false;
  if (sq.card() == 0) return true;
  DcmItem& last = *sq.getItem(sq.card() - 1);
  std::uint64_t elements = 0;
  for (unsigned long k = 0; k < last.card(); ++k) {
    if (last.getElement(k)->getLengthField() == DCM_UndefinedLength) return true;
    elements += extent(*last.getElement(k), explicit_vr);
  }
  if (elements < last.getLengthField()) return false;
  DcmElement* tail = last.card() ? last.getElement(last.card() - 1) : nullptr;
  return !tail || tail->ident() != EVR_SQ || holds_declared(*static_cast<DcmSequenceOfItems*>(tail), explicit_vr);
}

// Step 1b: a file cut short between two items or elements of its last sequence parses; its declared lengths
// tell. A cut between two top-level elements cannot be told from a file without them: the checks after this
// catch what is then missing (no ROI, no contours, no frame of reference).
void require_complete(DcmFileFormat& ff, const fs::path& file) {
  DcmDataset& ds = *ff.getDataset();
  if (ds.card() == 0) return;
  DcmElement* last = ds.getElement(ds.card() - 1);
  const bool explicit_vr = DcmXfer(ds.getOriginalXfer()).isExplicitVR();
  if (last->ident() == EVR_SQ && !holds_declared(*static_cast<DcmSequenceOfItems*>(last), explicit_vr))
    throw IoError(ErrorCode::Parse, at(file),
                  "truncated: the file ends inside " + std::string(DcmTag(last->getTag()).getTagName()) +
                      ", short of the length it declares",
                  "the file was cut short: copy it again");
}

DicomKind kind_of(DcmFileFormat& ff) {
  DicomKind k;
  OFString v;
  if (ff.getDataset()->findAndGetOFString(DCM_SOPClassUID, v).good() && !trim(v.c_str()).empty())
    k.sop_class_uid = trim(v.c_str());
  else if (ff.getMetaInfo()->findAndGetOFString(DCM_MediaStorageSOPClassUID, v).good())
    k.sop_class_uid = trim(v.c_str());
  if (ff.getDataset()->findAndGetOFString(DCM_Modality, v).good()) k.modality = trim(v.c_str());
  const char* name = k.sop_class_uid.empty() ? nullptr : dcmFindNameOfUID(k.sop_class_uid.c_str(), nullptr);
  k.sop_class = name ? words(name) : k.sop_class_uid;
  k.rtstruct = k.sop_class_uid == UID_RTStructureSetStorage || (k.sop_class_uid.empty() && k.modality == "RTSTRUCT");
  return k;
}

// Step 2: an RT structure set, or a message saying what the file is.
void require_rtstruct(DcmFileFormat& ff, const fs::path& file) {
  const DicomKind k = kind_of(ff);
  const std::string hint =
      "give the RT structure set (Modality RTSTRUCT, SOP class RT Structure Set Storage "
      "1.2.840.10008.5.1.4.1.1.481.3) that holds the contours";
  if (k.sop_class_uid.empty() && k.modality.empty())
    throw IoError(ErrorCode::Parse, at(file), "not a DICOM file: no SOP Class UID (0008,0016) and no Modality", hint);
  if (k.rtstruct && !k.modality.empty() && k.modality != "RTSTRUCT")
    throw IoError(
        ErrorCode::Format, at(file),
        "SOP class RT Structure Set Storage but Modality " + k.modality + ": not a consistent RT structure set", hint);
  if (k.rtstruct) return;
  const bool image = k.sop_class.find("Image") != std::string::npos;
  const std::string what = image ? "a " + (k.modality.empty() ? std::string("DICOM") : k.modality) + " image"
                                 : "a DICOM " + (k.modality.empty() ? std::string("object") : k.modality + " object");
  throw IoError(
      ErrorCode::Format, at(file),
      fmt::format("{} ({}{}), not an RT structure set", what, k.sop_class.empty() ? "no SOP class" : k.sop_class,
                  k.modality.empty() ? "" : ", Modality " + k.modality),
      hint);
}

// Step 3: the ROIs (StructureSetROISequence) and their interpreted types (RTROIObservationsSequence).
std::vector<Roi> read_rois(DcmDataset& ds, const fs::path& file) {
  DRTStructureSetROISequence seq;
  seq.read(ds, "1-n", "3", "StructureSetModule");
  std::vector<Roi> rois;
  std::set<int> numbers;
  for (std::size_t i = 0; i < seq.getNumberOfItems(); ++i) {
    const DRTStructureSetROISequence::Item& it = seq.getItem(i);
    Roi r;
    Sint32 n = 0;
    if (it.getROINumber(n).bad())
      throw IoError(ErrorCode::Format, at(file, fmt::format("StructureSetROISequence item {}", i)),
                    "no valid ROINumber (3006,0022)", "fix the structure set");
    if (!numbers.insert(n).second)
      throw IoError(ErrorCode::Format, at(file, fmt::format("StructureSetROISequence item {}", i)),
                    fmt::format("ROINumber {} is given twice", n), "fix the structure set");
    r.number = n;
    r.name = text([&](OFString& v) { return it.getROIName(v); });
    r.frame_of_reference = text([&](OFString& v) { return it.getReferencedFrameOfReferenceUID(v); });
    rois.push_back(std::move(r));
  }
  DRTRTROIObservationsSequence obs;
  obs.read(ds, "1-n", "3", "RTROIObservationsModule");
  for (std::size_t i = 0; i < obs.getNumberOfItems(); ++i) {
    const DRTRTROIObservationsSequence::Item& it = obs.getItem(i);
    Sint32 n = 0;
    if (it.getReferencedROINumber(n).bad()) continue;  // optional module: nothing to read
    for (Roi& r : rois)
      if (r.number == n) r.interpreted_type = text([&](OFString& v) { return it.getRTROIInterpretedType(v); });
  }
  return rois;
}

// "1.5\-2\3e1" -> {1.5, -2, 30}; DS values may carry spaces and a '+' sign. NaN and infinity pass (14 later).
bool parse_decimals(const std::string& s, std::vector<double>& out) {
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = std::min(s.find('\\', start), s.size());
    std::string item = trim(s.substr(start, end - start));
    if (!item.empty() && item[0] == '+') item.erase(0, 1);
    double v = 0;
    const auto [ptr, err] = std::from_chars(item.data(), item.data() + item.size(), v);
    if (item.empty() || err != std::errc() || ptr != item.data() + item.size()) return false;
    out.push_back(v);
    start = end + 1;
  }
  return true;
}

// One ContourSequence item: its points, or nothing when it is not a closed planar contour.
bool read_contour(const DRTContourSequence::Item& it, const Roi& roi, int k, const fs::path& file, RoiContour& out,
                  std::string& type) {
  const Location where = at(file, roi_part(roi), k);
  type = text([&](OFString& v) { return it.getContourGeometricType(v); });
  if (type.empty())
    throw IoError(ErrorCode::Format, where, "no ContourGeometricType (3006,0042)",
                  "each contour must say CLOSED_PLANAR, OPEN_PLANAR, OPEN_NONPLANAR or POINT");
  if (type != "CLOSED_PLANAR" && type != "CLOSED_PLANAR_XOR") return false;
  OFString data;
  it.getContourData(data, -1);
  std::vector<double> v;
  if (!data.empty() && !parse_decimals(data.c_str(), v))
    throw IoError(ErrorCode::Parse, where, "ContourData (3006,0050) is not a list of decimal numbers",
                  "the file may be corrupt");
  if (v.size() % 3 != 0)
    throw IoError(ErrorCode::Format, where, fmt::format("ContourData holds {} numbers, not x\\y\\z triplets", v.size()),
                  "fix the structure set");
  Sint32 n = -1;
  if (it.getNumberOfContourPoints(n).good() && static_cast<std::size_t>(n) * 3 != v.size())
    throw IoError(ErrorCode::Format, where,
                  fmt::format("NumberOfContourPoints is {} but ContourData holds {} points", n, v.size() / 3),
                  "fix the structure set");
  out.item = k;
  for (std::size_t i = 0; i + 2 < v.size(); i += 3) {
    const Vec3 p{v[i], v[i + 1], v[i + 2]};
    if (out.points.empty() || !(out.points.back() == p)) out.points.push_back(p);  // a repeated point
  }
  while (out.points.size() > 1 && out.points.back() == out.points.front()) out.points.pop_back();  // closing point
  return true;
}

// Step 4: each ROI's contours (ROIContourSequence).
void read_roi_contours(DcmDataset& ds, std::vector<Roi>& rois, const fs::path& file) {
  DRTROIContourSequence seq;
  seq.read(ds, "1-n", "3", "ROIContourModule");
  for (std::size_t i = 0; i < seq.getNumberOfItems(); ++i) {
    const DRTROIContourSequence::Item& it = seq.getItem(i);
    const Location where = at(file, fmt::format("ROIContourSequence item {}", i));
    Sint32 n = 0;
    if (it.getReferencedROINumber(n).bad())
      throw IoError(ErrorCode::Format, where, "no valid ReferencedROINumber (3006,0084)", "fix the structure set");
    const auto roi = std::find_if(rois.begin(), rois.end(), [&](const Roi& r) { return r.number == n; });
    if (roi == rois.end())
      throw IoError(ErrorCode::Format, where,
                    fmt::format("contours of ROI {}, which StructureSetROISequence does not define", n),
                    "fix the structure set");
    const DRTContourSequence& contours = it.getContourSequence();
    roi->has_contour_sequence = roi->has_contour_sequence || contours.getNumberOfItems() > 0;
    for (std::size_t k = 0; k < contours.getNumberOfItems(); ++k) {
      RoiContour c;
      std::string type;
      if (read_contour(contours.getItem(k), *roi, static_cast<int>(k), file, c, type))
        roi->contours.push_back(std::move(c));
      else
        ++roi->left_out[type];
    }
  }
}

// Step 5: the frames of reference the file references, and the image series under them.
References read_references(DcmDataset& ds) {
  References refs;
  DRTReferencedFrameOfReferenceSequence seq;
  seq.read(ds, "1-n", "3", "StructureSetModule");
  refs.present = seq.getNumberOfItems() > 0;
  for (std::size_t i = 0; i < seq.getNumberOfItems(); ++i) {
    DRTReferencedFrameOfReferenceSequence::Item& it = seq.getItem(i);
    const std::string uid = text([&](OFString& v) { return it.getFrameOfReferenceUID(v); });
    if (!uid.empty()) refs.frames_of_reference.insert(uid);
    DRTRTReferencedStudySequence& studies = it.getRTReferencedStudySequence();
    for (std::size_t s = 0; s < studies.getNumberOfItems(); ++s) {
      DRTRTReferencedSeriesSequence& series = studies.getItem(s).getRTReferencedSeriesSequence();
      for (std::size_t k = 0; k < series.getNumberOfItems(); ++k) {
        DRTRTReferencedSeriesSequence::Item& se = series.getItem(k);
        refs.series.emplace_back(text([&](OFString& v) { return se.getSeriesInstanceUID(v); }),
                                 se.getContourImageSequence().getNumberOfItems());
      }
    }
  }
  return refs;
}

std::string describe_left_out(const Roi& r) {
  if (!r.has_contour_sequence) return "no contours";
  std::string s;
  for (const auto& [type, n] : r.left_out) s += fmt::format("{}{} {}", s.empty() ? "" : ", ", n, type);
  return "no closed planar contour (" + s + ")";
}

std::string labels_present(const std::vector<Roi>& rois) {
  std::string s;
  for (const Roi& r : rois) s += fmt::format("{}\"{}\" ({})", s.empty() ? "" : ", ", r.label, roi_part(r));
  return s;
}

// Step 6: the ROIs asked for (options.label), each with contours.
std::vector<const Roi*> select_rois(const std::vector<Roi>& rois, const std::string& label, const fs::path& file,
                                    std::vector<std::string>& notes) {
  if (rois.empty())
    throw InvalidInput(ErrorCode::EmptyStructure, at(file), "the structure set defines no ROI",
                       "StructureSetROISequence (3006,0020) is empty or absent");
  if (label.empty() || label == "all") {
    std::vector<const Roi*> out;
    for (const Roi& r : rois) {
      if (!r.contours.empty())
        out.push_back(&r);
      else
        notes.push_back(fmt::format("{} ({}): {}, left out", roi_part(r), r.label, describe_left_out(r)));
    }
    if (out.empty())
      throw InvalidInput(ErrorCode::EmptyStructure, at(file, roi_part(rois.front())),
                         describe_left_out(rois.front()) + (rois.size() > 1 ? ", nor has any other ROI" : ""),
                         "the structure set holds no contour to reconstruct");
    return out;
  }
  const Roi* hit = nullptr;
  for (const Roi& r : rois)
    if (!hit && r.label == label) hit = &r;
  for (const Roi& r : rois)
    if (!hit && lower(r.name) == lower(label)) hit = &r;
  for (const Roi& r : rois)
    if (!hit && std::to_string(r.number) == label) hit = &r;
  if (!hit)
    throw InvalidInput(ErrorCode::UnknownLabel, at(file), "no ROI is called \"" + label + "\"",
                       "labels present: " + labels_present(rois));
  if (hit->contours.empty())
    throw InvalidInput(ErrorCode::EmptyStructure, at(file, roi_part(*hit)), describe_left_out(*hit),
                       "choose an ROI with contours: " + labels_present(rois));
  return {hit};
}

// Step 7: every ROI read is drawn in a frame of reference the file references, and all in the same one.
void check_geometry(const std::vector<const Roi*>& rois, const References& refs, const fs::path& file) {
  const std::string hint =
      "the contours' coordinates mean nothing without it: export the structure set again with its referenced "
      "frame of reference (ReferencedFrameOfReferenceSequence (3006,0010), ReferencedFrameOfReferenceUID "
      "(3006,0024))";
  if (!refs.present)
    throw InvalidInput(ErrorCode::MissingGeometry, at(file),
                       "no ReferencedFrameOfReferenceSequence (3006,0010): the frame of reference the contours "
                       "are drawn in is not given",
                       hint);
  for (const Roi* r : rois) {
    if (r->frame_of_reference.empty())
      throw InvalidInput(ErrorCode::MissingGeometry, at(file, roi_part(*r)),
                         "no ReferencedFrameOfReferenceUID (3006,0024)", hint);
    if (!refs.frames_of_reference.count(r->frame_of_reference))
      throw InvalidInput(
          ErrorCode::MissingGeometry, at(file, roi_part(*r)),
          "frame of reference " + r->frame_of_reference + " is not in ReferencedFrameOfReferenceSequence (3006,0010)",
          hint);
    if (r->frame_of_reference != rois.front()->frame_of_reference)
      throw IoError(ErrorCode::Format, at(file, roi_part(*r)),
                    "drawn in another frame of reference than " + roi_part(*rois.front()) +
                        ": their coordinates cannot be used together",
                    "read one ROI at a time with --label");
  }
}

// Newell's area vector of a polygon (normal × area, mm²).
Vec3 area_vector(const std::vector<Vec3>& p) {
  Vec3 a{0, 0, 0};
  if (p.size() < 3) return a;
  for (std::size_t i = 0; i < p.size(); ++i) a = a + cross(p[i] - p[0], p[(i + 1) % p.size()] - p[0]);
  return 0.5 * a;
}

Vec3 centroid(const std::vector<Vec3>& p) {
  Vec3 c{0, 0, 0};
  for (const Vec3& q : p) c = c + q;
  return p.empty() ? c : (1.0 / static_cast<double>(p.size())) * c;
}

// Step 8: slice ids from the planes: offsets along the mean contour normal (each area vector turned towards
// the largest one's; the largest component made positive), in order; a new slice starts `gap` mm past the
// first contour of the last one.
void assign_slices(std::vector<RawContour>& raw, double gap) {
  std::vector<Vec3> areas;
  std::size_t largest = 0;
  for (const RawContour& rc : raw) {
    areas.push_back(area_vector(rc.contour.points));
    if (norm(areas.back()) > norm(areas[largest])) largest = areas.size() - 1;
  }
  Vec3 n{0, 0, 0};
  for (const Vec3& a : areas) n = n + (dot(a, areas[largest]) < 0 ? -1.0 : 1.0) * a;
  n = norm(n) > 0 ? normalized(n) : Vec3{0, 0, 1};
  const double big = std::abs(n.x) >= std::max(std::abs(n.y), std::abs(n.z)) ? n.x
                     : std::abs(n.y) >= std::abs(n.z)                        ? n.y
                                                                             : n.z;
  if (big < 0) n = -n;  // its largest component positive: axial slice ids count towards the head (LPS +z)
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t i = 0; i < raw.size(); ++i) order.emplace_back(dot(centroid(raw[i].contour.points), n), i);
  std::sort(order.begin(), order.end());
  int id = -1;
  double first = -INFINITY;
  for (const auto& [offset, i] : order) {
    if (!(offset - first <= gap)) {  // NaN offsets start slices of their own (build_sequence refuses them)
      ++id;
      first = offset;
    }
    raw[i].contour.slice = id;
  }
}

// Step 9: the ROIs' contours as one frame, in ROI order then contour order; `origin` maps each contour's
// index back to its ROI and ContourSequence item.
std::vector<RawContour> raw_contours(const std::vector<const Roi*>& rois, const std::string& space, double gap,
                                     std::vector<std::pair<const Roi*, int>>& origin) {
  std::vector<RawContour> raw;
  for (const Roi* r : rois)
    for (const RoiContour& c : r->contours) {
      RawContour rc;
      rc.frame = 0;
      rc.index = static_cast<int>(raw.size());
      rc.contour.label = r->label;
      rc.contour.points = c.points;
      if (space == "RAS")
        for (Vec3& p : rc.contour.points) p = {-p.x, -p.y, p.z};
      origin.emplace_back(r, c.item);
      raw.push_back(std::move(rc));
    }
  assign_slices(raw, gap);
  return raw;
}

// Step 10: the validated stack; a failure names the ROI and its ContourSequence item.
Sequence validated(std::vector<RawContour>& raw, const std::vector<std::pair<const Roi*, int>>& origin,
                   const fs::path& file, const RtStructOptions& options, std::vector<ContourRepair>& repairs) {
  if (options.repair) {
    RepairOptions ro;
    ro.min_plane_gap = options.stack.min_plane_gap;
    repairs = repair_contours(raw, ro);
    for (ContourRepair& r : repairs)
      if (r.contour >= 0 && static_cast<std::size_t>(r.contour) < origin.size())
        r.detail = fmt::format("{}, contour {}: {}", roi_part(*origin[static_cast<std::size_t>(r.contour)].first),
                               origin[static_cast<std::size_t>(r.contour)].second, r.detail);
  }
  try {
    return build_sequence(raw, 1, {0.0}, file.string(), options.stack);
  } catch (const Error& e) {
    const int k = e.where().contour;
    if (k < 0 || static_cast<std::size_t>(k) >= origin.size()) throw;
    Location where = e.where();
    where.part = roi_part(*origin[static_cast<std::size_t>(k)].first);
    where.contour = origin[static_cast<std::size_t>(k)].second;
    throw InvalidInput(e.code(), where, e.detail(), e.hint());
  }
}

std::vector<std::string> summary_notes(const std::vector<const Roi*>& rois, const References& refs, const Sequence& seq,
                                       const std::string& space) {
  std::vector<std::string> notes;
  std::string list;
  for (const Roi* r : rois)
    list += fmt::format("{}{} -> {} ({}{} contours)", list.empty() ? "" : "; ", roi_part(*r), r->label,
                        r->interpreted_type.empty() ? "" : r->interpreted_type + ", ", r->contours.size());
  notes.push_back(fmt::format("RT structure set: {} ROI(s) read: {}", rois.size(), list));
  for (const auto& [uid, images] : refs.series)
    notes.push_back(
        fmt::format("referenced series {} ({} contour images; not read: slices are the contours' own "
                    "planes, normal ({:.4f}, {:.4f}, {:.4f}) from the contours)",
                    uid.empty() ? "(no UID)" : uid, images, seq.normal.x, seq.normal.y, seq.normal.z));
  notes.push_back("one frame: an RT structure set is one 3D time point");
  notes.push_back("coordinates: " + space + " mm (DICOM patient space" + (space == "RAS" ? ", x and y negated)" : ")"));
  return notes;
}

}  // namespace

bool is_dicom_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  char head[132] = {};
  return in.read(head, sizeof head) && std::string_view(head + 128, 4) == "DICM";
}

DicomKind dicom_kind(const fs::path& file) {
  std::unique_ptr<DcmFileFormat> ff = load(file);
  return kind_of(*ff);
}

std::string roi_label(const std::string& roi_name, int roi_number) {
  std::string s;
  for (const char ch : roi_name) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x80 && std::isalnum(c))
      s += static_cast<char>(std::tolower(c));
    else if (!s.empty() && s.back() != '-')
      s += '-';
  }
  while (!s.empty() && s.back() == '-') s.pop_back();
  if (s.empty()) return "roi-" + std::to_string(roi_number);
  if (s == "all") return "all-" + std::to_string(roi_number);
  return s;
}

InputResult read_rtstruct(const fs::path& file, const RtStructOptions& options) {
  if (options.space != "LPS" && options.space != "RAS")
    throw InvalidInput(ErrorCode::Usage, at(file), "unknown space '" + options.space + "'", "use LPS or RAS");
  std::unique_ptr<DcmFileFormat> ff = load(file);
  require_rtstruct(*ff, file);
  require_complete(*ff, file);
  DcmDataset& ds = *ff->getDataset();
  std::vector<Roi> rois = read_rois(ds, file);
  std::set<std::string> taken;
  for (Roi& r : rois) {
    r.label = roi_label(r.name, r.number);
    if (!taken.insert(r.label).second) r.label += "-" + std::to_string(r.number);  // two ROIs of one name
  }
  read_roi_contours(ds, rois, file);
  const References refs = read_references(ds);

  InputResult result;
  const std::vector<const Roi*> chosen = select_rois(rois, options.label, file, result.notes);
  check_geometry(chosen, refs, file);
  std::vector<std::pair<const Roi*, int>> origin;
  std::vector<RawContour> raw = raw_contours(chosen, options.space, options.stack.min_plane_gap, origin);
  for (const Roi* r : chosen)
    for (const auto& [type, n] : r->left_out)
      result.notes.push_back(fmt::format("{}: {} {} contour(s) left out (not closed planar)", roi_part(*r), n, type));
  result.sequence = validated(raw, origin, file, options, result.repairs);
  result.sequence.space = options.space;
  result.format = "dicom-rtstruct";
  const std::vector<std::string> summary = summary_notes(chosen, refs, result.sequence, options.space);
  result.notes.insert(result.notes.begin(), summary.begin(), summary.end());
  return result;
}

}  // namespace c4d
