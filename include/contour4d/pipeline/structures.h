#pragma once
//! \file structures.h
//! \brief Every structure of a heart in one run: the input split into one sequence per structure (a
//! contour label), and the myocardial wall made from the endocardium inside the epicardium on each slice.

#include <string>
#include <vector>

#include "contour4d/io/input_result.h"

namespace c4d {

//! Myocardial density (g/ml): wall mass = wall volume × this (the value cardiac MRI tools use).
constexpr double kMyocardiumDensity = 1.05;

//! The wall's name, and the labels it is made from.
inline const std::string kLvWall = "lv-wall";
inline const std::string kLvEndo = "lv-endo";
inline const std::string kLvEpi = "lv-epi";

//! One structure to reconstruct on its own.
struct Structure {
  std::string name;         //!< its label ("lv-endo", "lv-wall", "3", ...)
  InputResult input;        //!< its contours only, every contour labelled `name`; frames without any dropped
  std::vector<int> frames;  //!< the input frame of each frame kept
  bool wall = false;        //!< the myocardial wall (its volume gives the mass)
};

//! The structures `asked` names: {"all"} is every label of the input, plus lv-wall when lv-endo and lv-epi
//! are both present; otherwise the names given (lv-wall included). Notes say which frames and slices a
//! structure lacks. \throw InvalidInput (UnknownLabel) for a name the input does not hold.
std::vector<Structure> split_structures(const InputResult& read, const std::vector<std::string>& asked);

//! The wall between `inner` and `outer` contours, labelled `name`: on each slice the outer contours and the
//! inner ones lying inside them (holes). A slice whose inner contour is not inside an outer one (drawn across
//! it) is left out of that frame, and so is an inner contour on a slice without outer ones; each is noted.
Sequence wall_sequence(const Sequence& seq, const std::string& inner, const std::string& outer, const std::string& name,
                       std::vector<std::string>& notes);

}  // namespace c4d
