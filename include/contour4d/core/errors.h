#pragma once
//! \file errors.h
//! \brief Exceptions with context (file, place, hint) and the CLI exit code of each failure class.
//!
//! Every bad input gets its own exit code, so scripts can tell failures apart (docs/cli.md lists
//! them). Messages read "FILE: line L, frame F, slice S, contour C: what. hint".

#include <stdexcept>
#include <string>

namespace c4d {

//! Exit codes of the command-line tool, one per failure class (0 is success).
enum class ErrorCode : int {
  Internal = 1,            //!< a bug: please report it
  Usage = 2,               //!< bad command line
  FileNotFound = 10,       //!< input file or folder missing or unreadable
  EmptyFile = 11,          //!< input file has no content
  Parse = 12,              //!< syntax error, truncated file, malformed line
  Format = 13,             //!< wrong format name, version or units
  NonFinite = 14,          //!< NaN or infinite coordinate
  DegenerateContour = 15,  //!< fewer than 3 distinct points, or zero area
  SelfIntersection = 16,   //!< contour crosses itself
  NotCoplanar = 17,        //!< contours of one slice do not lie on one plane
  NotParallel = 18,        //!< slices are not parallel
  DuplicatePlane = 19,     //!< two slice ids lie on one plane
  EmptyFrame = 20,         //!< a frame has no contours
  UnknownLabel = 21,       //!< the requested label / contour type is absent
  MissingCompanion = 22,   //!< a file the input needs beside it is missing (e.g. SliceInfoFile.txt)
  OutputNotWritable = 23,  //!< output folder cannot be created or written
  NotImplemented = 24,     //!< the requested stage is not available yet
  BadMesh = 25,            //!< a mesh file that cannot be read or is inconsistent
  InvalidResult = 26,      //!< a reconstructed frame failed its checks before writing (not closed or manifold,
                           //!< inward, self-intersecting, volume far from Simpson's discs): nothing is written
  MissingGeometry = 27,    //!< contours without the geometry they are drawn in (an RT structure set whose ROI names
                           //!< no frame of reference, or one the file does not reference)
  EmptyStructure = 28,     //!< a structure without contours (an RT structure set's ROI with no closed planar
                           //!< contour, or a structure set without ROIs)
  TooFewFrames = 29,       //!< `export`: the output folder holds one frame (a --frame run), not a cycle
  OpenSurface = 30,        //!< `export`: the surface has holes (reconstructed with --cap open); it opens ends itself
  InvertedElement = 31,    //!< `export`: the moving cavity mesh or a flattened end folds at some time: nothing written
  UnknownFrameTimes = 32,  //!< `export`: the frame times are unknown (GPFiles, images): give --frame-ms or --cycle-ms
  VolumeMeshFailed = 33,   //!< `export`: the cavity could not be tetrahedralised with its surface kept
};

//! Where in an input a problem was found; unset fields are omitted from messages.
struct Location {
  std::string file;            //!< path of the file or folder
  int line = -1;               //!< 1-based line
  int frame = -1;              //!< 0-based frame index
  int slice = -1;              //!< slice id
  int contour = -1;            //!< 0-based contour index within the frame (within `part` when that is set)
  std::string part{};          //!< a named part of the file, e.g. `ROI 2 "Lung L"` of an RT structure set
  std::string format() const;  //!< "file: ROI 2 "Lung L", line 3, frame 0, slice 2, contour 1"
};

//! Base of all contour4d exceptions: a message with context and an exit code.
class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const Location& where, const std::string& what, const std::string& hint = {});
  ErrorCode code() const { return code_; }
  const Location& where() const { return where_; }
  const std::string& detail() const { return detail_; }  //!< the `what` given, without place and hint
  const std::string& hint() const { return hint_; }

 private:
  ErrorCode code_;
  Location where_;
  std::string detail_;
  std::string hint_;
};

//! A file could not be read or written.
class IoError : public Error {
 public:
  using Error::Error;
};

//! The input data violates the model (bad values, geometry or structure).
class InvalidInput : public Error {
 public:
  using Error::Error;
};

//! A numerical stage failed (factorisation, no convergence).
class SolverError : public Error {
 public:
  using Error::Error;
};

}  // namespace c4d
