#pragma once
// A study run inside this process: what `import bounce`'s sweep() does. Every job runs through
// study::runJob, the function each `bounce sweep --job ID` worker calls, one at a time in stage order
// on the process's GL context; finished jobs are skipped and a job whose input failed is not started,
// as `bounce sweep --jobs 1` does with worker processes (SweepCommand.cpp).
#include "app/Study.h"

#include <functional>
#include <string>
#include <vector>

namespace bounce::study {

// OUTPUT/study.json: the study as given plus its job list, for the report and for people.
Expected<void> writeStudyCopy(const Study& study);

struct InProcessRun {
    size_t jobs = 0, ran = 0, finishedBefore = 0, refused = 0;  // refused: refused or skipped by the technique
    std::vector<std::string> failed;                            // ids, with the reason after ": "
    size_t blocked = 0;                                         // not started: an input failed
};

// Called before each job runs with its index among the pending ones.
using JobCallback = std::function<void(const Job& job, size_t index, size_t pending)>;

Expected<InProcessRun> runStudyInProcess(const Study& study, const JobCallback& before = {});

}  // namespace bounce::study
