#include "contour4d/core/errors.h"

#include <sstream>

namespace c4d {

std::string Location::format() const {
  std::ostringstream os;
  bool first = true;
  auto sep = [&] {
    os << (first ? "" : ", ");
    first = false;
  };
  if (!file.empty()) {
    os << file;
    first = true;
    if (!part.empty() || line >= 0 || frame >= 0 || slice >= 0 || contour >= 0) os << ": ";
  }
  if (!part.empty()) {
    sep();
    os << part;
  }
  if (line >= 0) {
    sep();
    os << "line " << line;
  }
  if (frame >= 0) {
    sep();
    os << "frame " << frame;
  }
  if (slice >= 0) {
    sep();
    os << "slice " << slice;
  }
  if (contour >= 0) {
    sep();
    os << "contour " << contour;
  }
  return os.str();
}

namespace {
std::string compose(const Location& where, const std::string& what, const std::string& hint) {
  std::string msg = where.format();
  if (!msg.empty()) msg += ": ";
  msg += what;
  if (!hint.empty()) msg += ". " + hint;
  return msg;
}
}  // namespace

Error::Error(ErrorCode code, const Location& where, const std::string& what, const std::string& hint)
    : std::runtime_error(compose(where, what, hint)), code_(code), where_(where), detail_(what), hint_(hint) {}

}  // namespace c4d
