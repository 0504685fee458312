// fuzz_world.h — runs one recipe on stock btDiscreteDynamicsWorld or on btGpuDynamicsWorld
// through the public API only, and records what a verdict needs: which bodies the app made
// bad (and when), which the world named, which went non-finite, what each call returned.
#pragma once
#include "fuzz_recipe.h"

#include <LinearMath/btVector3.h>

#include <string>
#include <vector>

namespace btgpu::fuzz {

enum class Engine { Stock, Gpu };

struct BodyTrace {
    bool built = false;         // part of this run (stock leaves out what it cannot survive)
    std::string badWhy;         // first reason its own input was not finite ("" = never bad)
    int badAtCall = -1;         // the step call it was first bad at
    bool mustBeNamed = false;   // bad and in the world when a call simulated
    std::string mustPath;       // "gpu" or "cpu": the path of that call
    bool named = false;         // a BadBody issue named it by index
    std::string namedBy;        // that issue's message
    int namedAtCall = -1;       // the call that issue came with
    int nonFiniteAtCall = -1;   // first call after which its state was not finite
    float maxSpeed = 0.0f;      // m/s, largest linear speed seen after a call
    int maxSpeedAtCall = -1;    // that call
};

struct CallTrace {
    int op = -1;                // index in Recipe::ops (-1: one of the closing steps)
    float dt = 0.0f, fixedStep = 0.0f;
    int maxSubSteps = 0;
    ArgClass cls = ArgClass::Normal;
    bool ran = false;           // run on this engine (stock skips bad arguments)
    int returned = 0;
    bool changedBodies = false; // a bad or ambiguous call moved a body or a motion state
    bool reported = false;      // a bad or ambiguous call came with an issue naming the argument
    std::string gpuPath;        // "gpu" / "cpu" after the call (btgpu only)
    unsigned long long stateHash = 0;  // FNV-1a of every built body's transform and velocities after it
};

struct Trace {
    std::vector<BodyTrace> bodies;  // by recipe body index
    std::vector<CallTrace> calls;
    std::vector<std::string> exceptions;   // anything that escaped a Bullet call
    std::vector<std::string> badIndex;     // BadBody issues whose bodyIndex names no object
    std::vector<std::string> namedOthers;  // BadBody issues naming the plane or the closing probe
    std::string cpuReason;                 // the last CPU-path reason seen ("" = always GPU)
    int issues = 0;
    btVector3 probePos{0, 0, 0};  // the probe after the recipe's own calls
    bool probeFinite = true;
    float probeDv = 0.0f;         // change of the probe's vertical velocity over the closing steps
    float lateProbeDv = 0.0f;     // same, for a sphere added just before them
    bool lateProbeFinite = true;
};

struct RunOptions {
    bool stockEverything = false;  // stock also gets the ops marked unsafe for it (exploring)
};

// The recipe's ops in order, then the closing check: world gravity back to (0, -10, 0), a
// sphere added far away, three variable steps of 1/60 s that the probe and it must fall through.
Trace run(const Recipe& recipe, Engine engine, const RunOptions& options = RunOptions());

}  // namespace btgpu::fuzz
