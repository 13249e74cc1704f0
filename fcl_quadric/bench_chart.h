#pragma once
/// \file bench_chart.h
/// The bar chart `fcl_quadric bench` draws per experiment (Cairo PNG): one horizontal bar per
/// (case, peer), grouped by case, coloured by peer, each labelled with its value and its ratio to
/// fcl_quadric; the time axis is logarithmic when the times span more than 10x.

#include <string>

#include "fcl_quadric/bench_experiments.h"

namespace fcl_quadric {
namespace cli {

/// Writes the chart of `e` (ratios filled in) to the PNG file `path`.
/// \throws SceneError when the file cannot be written.
void writeBenchChart(const BenchExperiment& e, const std::string& path);

}  // namespace cli
}  // namespace fcl_quadric
