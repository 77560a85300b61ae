// The printing of `vcpost deff`: an evaluation (postproc/deff/) as an
// aligned text table, JSON or CSV cells. Writes only to the streams it is
// given.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>

#include "postproc/deff/evaluation.h"

namespace vcpost::cli::deff_printing {

using vcpost::deff::Description;
using vcpost::deff::Evaluation;
using vcpost::deff::Speed;

// Human-readable report: set-up, an aligned table of D_max, D_min, D_mean
// and the cutting points (position, 2r, r with `radius`, vc with a speed),
// flags, milling mode and spindle speed.
void write_table(std::ostream& out, const Description& description, const Evaluation& evaluation,
                 const std::optional<Speed>& speed, bool radius);

// Machine-readable report; keys documented in README.md ("vcpost deff").
nlohmann::ordered_json to_json(const Description& description, const Evaluation& evaluation,
                               const std::optional<Speed>& speed);

// The result columns shared by --sweep and --batch:
// d_cut,d_p1,d_p2,d_p1a,d_p1b,d_p2a,d_p2b,d_max,d_min,d_mean,engaged and,
// with `radius`, r_cut ... r_mean after them. Cells: mm with 4 decimals,
// empty where a point does not exist; engaged 0 or 1.
std::string csv_header(bool radius);
std::string csv_cells(const Evaluation& evaluation, bool radius);

}  // namespace vcpost::cli::deff_printing
