#pragma once
/// \file
/// The PRADIS model language (docs/language.md): lexer, parser, builder/runner.
///
///     auto prog = pradis::lang::parse_file("model.prd");
///     pradis::lang::session s(std::move(prog));   // builds and checks the model
///     s.run({.output_dir = "out", .stem = "model"});

#include "pradis/lang/ast.hpp"
#include "pradis/lang/builtin.hpp"
#include "pradis/lang/catalog.hpp"
#include "pradis/lang/commands.hpp"
#include "pradis/lang/lexer.hpp"
#include "pradis/lang/parser.hpp"
#include "pradis/lang/session.hpp"
#include "pradis/lang/source.hpp"
