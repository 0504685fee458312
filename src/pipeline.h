// pipeline.h — the whole step on the device: the substeps of one stepSimulation call,
// enqueued back to back with no host round trip, plus the snapshot that lets the caller redo
// the call after a buffer overflowed.
#pragma once
#include "stages/sync_bodies.h"
#include "world/device_world.h"
#include "world/plan.h"

#include <btgpu/Config.h>

#include <functional>
#include <string>
#include <vector>

namespace btgpu {

// How much of the call's last substep runs: all of it; all but the deactivation, so that the
// host can run the app's actions in between, as Bullet's internalSingleStepSimulation runs
// updateActions after integrateTransforms and before updateActivationState; or only that
// deactivation, the rest of a substep stopped before it (one substep, the counters and the
// constraint graph as it left them).
enum class SubstepPart { Whole, BeforeActivation, ActivationOnly };

// Where the host steps in inside a substep for the app's contact callbacks
// (compat/contact_callbacks.h): nowhere; the substep up to its contacts found (manifolds and
// forces), stopped before the contact list; or the rest of it from the contact list on.
enum class ContactsSplit { None, UntilContacts, FromContacts };

struct StepSettings {
    BtgStepParams params;  // dt is the fixed substep
    int substeps = 1;
    SubstepPart lastPart = SubstepPart::Whole;
    ContactsSplit split = ContactsSplit::None;  // of the call's one substep (substeps must be 1)
    int iterations = 10;   // btContactSolverInfo::m_numIterations
    int maxColors = 24;    // BatchedPgs only
    SolverKind solver = SolverKind::BatchedPgs;  // must match the plan's
    SoftStepConfig soft;   // SolverKind::SoftStep only
    BtgJointStepParams joints{};  // the joints' solver settings (numJoints 0: none)
};

// Enqueues `s.substeps` substeps of the plan (the caller reads back once afterwards).
void runSubsteps(DeviceWorld& w, const Plan& plan, const StepSettings& s);

// What a redo needs: the body state and the counters as they were before the call. The
// warm-start cache needs nothing here: a substep that overflows leaves it untouched
// (store_contact_cache checks the status), and when a call runs several substeps runSubsteps
// keeps a copy of it (DeviceWorld::contactCacheAtCall) that restoreSnapshot puts back.
struct Snapshot {
    cl::DeviceArray<BtgFloat4> pos, rot, linVel, angVel;
    cl::DeviceArray<uint> counters;
    cl::DeviceArray<BtgJointState> jointState;  // breaks made by a call that is redone are undone
};
void takeSnapshot(DeviceWorld& w, Snapshot& s);
void restoreSnapshot(DeviceWorld& w, Snapshot& s);

// Clears the status word and the NaN marker at the start of a call.
void resetStatus(DeviceWorld& w);

// What happened on the way through a call that its caller reports: a buffer grew, or this
// device turned out not to keep a launch's work-groups resident (one-launch stages off).
struct CallEvent {
    enum class Kind { Grew, ResidentOff };
    Kind kind;
    std::string message;
};
struct CallOutcome {
    std::vector<CallEvent> events;
    int redone = 0;  // times the call was redone
    bool abandoned = false;  // betweenContacts refused: the call stopped before its contact list
};

// One stepSimulation call's device work: s.substeps substeps of the plan and one readback
// into rb. A buffer that overflowed grows and the call is redone from the snapshot, so no pair
// or contact is ever dropped; a grid-barrier timeout turns the one-launch stages off for good
// and redoes the call. Sets the next call's coloring rounds from this one's.
// betweenContacts (a call of one substep whose plan collides): the substep stops once its
// contacts are found, with no buffer overflowed so far, for the host (the app's contact
// callbacks), and goes on when it returns true; false abandons the call (nothing read back: the
// caller runs the step elsewhere). A redo after a later overflow asks it again.
CallOutcome runCall(DeviceWorld& w, const Plan& plan, const StepSettings& s, Snapshot& snapshot, BodyReadback& rb,
                    const std::function<bool()>& betweenContacts = {});

}  // namespace btgpu
