// accuracy_cases.h — btgpu_accuracy's reference scenes with their error measures: a Case
// builds the scene (tests/scenes/accuracy_scenes.h) and a Probe that watches it frame by frame
// and condenses what it saw into one error (with its unit) plus penetration and notes.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pile_stats.h"
#include "scenes/accuracy_scenes.h"

namespace btgpu::accuracy {

struct Measurement {
    double error = 0;        // in the case's unit; NaN when it could not be measured
    double penetration = 0;  // m, deepest penetration seen (resting scenes, pile); 0 elsewhere
    std::string notes;       // key=value;... details (the parts of a combined error)
};

class Probe {
public:
    virtual ~Probe() = default;
    // Called before the first step (t = 0) and after every 1/60 s frame; t in simulated seconds.
    virtual void sample(const scenes::AccuracyScene& a, int frame, double t) = 0;
    virtual Measurement finish(const scenes::AccuracyScene& a) = 0;
};

struct Case {
    std::string name, description;
    std::string errorLabel;  // the y axis: what the error is, with its unit
    double seconds = 1;      // simulated
    // copies: of a one-body scene; scenes of many bodies build fewer copies (or one).
    std::function<scenes::AccuracyScene(scenes::WorldKind, const Config&, int copies)> make;
    std::function<std::unique_ptr<Probe>()> probe;
};

// The pile's converged reference (btgpu_accuracy_reference's file); empty rows when absent.
struct PileReference {
    int dims[3] = {0, 0, 0};
    double seconds = 0;
    std::string settings;
    std::vector<PileStats> rows;  // every kPileSampleSeconds from t = 0
};
bool readPileReference(const std::string& path, PileReference& out, std::string& why);

// Every case; quick shortens the runs. The pile uses the reference's size and duration, or
// (no reference) 10x10x10 / 5x4x5 quick and reports no error.
std::vector<Case> makeCases(bool quick, const PileReference& pile);

}  // namespace btgpu::accuracy
