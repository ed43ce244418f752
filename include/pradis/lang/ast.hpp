#pragma once
/// \file
/// The syntax tree of a model file (what the parser produces; the builder gives it meaning).

#include <string>
#include <vector>

#include "pradis/lang/source.hpp"

namespace pradis::lang::ast {

/// One entry of an argument or value list.
struct item {
  enum class kind {
    number,  ///< a number literal: `5E3`
    name,    ///< a $DATA name (words joined by single blanks), possibly negated: `-Force`
    keyed,   ///< KEY = value: `END=1`; `value` holds the value (a number or name item)
    work     ///< a work-vector entry W:Name(k): `text` is the element name, `index` is k
  };
  kind what = kind::number;  ///< which of the forms above
  location loc;              ///< where the item starts
  double number = 0;         ///< number: its value
  std::string text;  ///< name, key (upper case) or element name
  bool negate = false;       ///< name: written with a leading '-'
  int index = 0;            ///< work: k
  location index_loc;       ///< work: where k is
  std::vector<item> value;  ///< keyed: exactly one item
};

/// Argument groups of a call, separated by ';'; items in a group by ',' (numbers also by blanks).
using groups = std::vector<std::vector<item>>;

/// `Label 'PROGRAM (args)`: an element or fragment instance, an output, a run stage or a display.
struct call {
  location loc;          ///< start of the statement
  std::string label;     ///< label words joined by single blanks (may be empty)
  location program_loc;  ///< where the program name is
  std::string program;   ///< program / model name, upper case
  location args_loc;     ///< where '(' is (or the program name if there are no arguments)
  groups args;
};

/// `Name = item, item, ...` in $DATA or $REPLACE.
struct definition {
  location loc;
  std::string name;
  std::vector<item> values;
};

/// `$FRAGMENT [name]` with its subsections.
struct fragment {
  location loc;
  std::string name;  ///< empty: the main model
  bool has_structure = false;
  location external_loc;
  std::vector<item> external;  ///< #EXTERNAL node numbers (sub-structures)
  bool has_external = false;
  std::vector<call> structure;  ///< #STRUCTURE
  std::vector<call> outputs;    ///< #OUTPUT
};

/// One thing the file asks to do after the model is built, in file order.
struct action {
  enum class kind { run, print, replace, restore, save };
  kind what = kind::run;
  location loc;
  call stage;                           ///< run, print
  std::vector<definition> definitions;  ///< replace
  std::string path;                     ///< restore, save
};

/// A whole model file (with its included files merged in).
struct program {
  std::vector<definition> data;
  std::vector<fragment> fragments;
  std::vector<action> actions;
  location end;  ///< where $END is (or the end of the file)
  bool has_end = false;
};

}  // namespace pradis::lang::ast
