// fuzz_verdict.h — what a fuzz scene must show: no exception, no NaN in a well-formed body (an
// extreme one only where stock keeps it finite), every bad body named by index and no good one,
// bad stepSimulation arguments a reported no-op, substeps as stock's, the probe still falling.
#pragma once
#include "fuzz_recipe.h"
#include "fuzz_world.h"

#include <string>
#include <vector>

namespace btgpu::fuzz {

struct Failure {
    std::string kind;    // stable class name, for grouping seeds ("nan-wellformed", "unnamed-bad(gpu: friction ...)")
    std::string detail;  // which body or call, and what was seen
};

// stock may be null (not run); then extreme bodies are not asserted finite. notes, if given,
// gets what is not asserted but worth a line (a well-formed body NaN on both engines).
std::vector<Failure> judge(const Recipe& recipe, const Trace& gpu, const Trace* stock, std::vector<Failure>* notes = nullptr);

// What stock Bullet itself did with the scene, for the record (never a failure of btgpu).
std::vector<std::string> stockNotes(const Recipe& recipe, const Trace& stock);

// Every body's and call's record, for reading one seed (printed when BTGPU_FUZZ_SCENES=1).
std::string dump(const Recipe& recipe, const Trace& trace);

}  // namespace btgpu::fuzz
