// The columns of series.csv and the values of one row, shared by the file's writer and the
// window's plots, so a column plotted in the window is the column the run writes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "solve/simulation.h"
#include "solve/snapshot.h"

namespace periflex {

// Column names in file order: time, energies, violations, then the damage columns (scenes with
// particles), the contact columns (scenes with [[contact]]) and the probe columns.
std::vector<std::string> series_columns(const std::vector<std::string>& probe_columns, bool with_damage,
                                        bool with_contact);

// The columns of a run of `sim`'s scene (its probes, damage columns with particles, contact
// columns with [[contact]]).
std::vector<std::string> series_columns(const Simulation& sim);

// The same columns from the scene's definitions alone, before any model is built: what a sweep
// checks the column names it gathers against. The model resolves the probes on flexible bodies
// with the bodies, so those come first, then the rigid bodies' probes, each in scene order.
std::vector<std::string> series_columns(const SceneDef& scene);

// The values of `sample` in the order of series_columns (out is replaced).
void series_values(const Sample& sample, bool with_damage, bool with_contact, std::vector<double>& out);

// Puts the row series.csv would hold now into the snapshot, for the plots: its columns are made
// once into `columns` and shared by every snapshot after.
void fill_series_row(const Simulation& sim, std::shared_ptr<const std::vector<std::string>>& columns, Snapshot& out);

// The unit of a column as docs/running.md states it ("s", "J", "m", "m/s", "rad", "rad/s", "N",
// "1/s"), "-" for counts and fractions, "" for a column it does not know.
std::string series_unit(const std::string& column);

}  // namespace periflex
