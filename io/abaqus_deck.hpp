#pragma once
// Abaqus / CalculiX input decks (.inp) read as rigflex models: the model
// data of a flat (part-less) deck and the boundary conditions of a
// *FREQUENCY step. What each keyword and element type becomes, and what is
// refused, is listed in docs/model-exchange.md; anything the reader does not
// take is an InputError naming the file, line and keyword, never skipped.
// Units are as given: rigflex computes in whatever consistent set the deck
// uses (SI, or N-mm-t-s, whose frequencies are the same).
#include <string>

#include "io/model_reader.hpp"

namespace rigflex::io {

// `source` names the deck in errors and locates its *INCLUDE files.
ModelFile parse_abaqus_deck(const std::string& text, const std::string& source);

}  // namespace rigflex::io
