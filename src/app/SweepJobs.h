#pragma once
// Running one job of a study (`bounce sweep STUDY.json --job ID`): the same code path whether the
// job runs under the local runner, GNU parallel or a Slurm array task, so every route gives the same
// records. Outputs go to OUTPUT/ID/; the record OUTPUT/ID/record.json is written last (atomically),
// and only a record whose spec matches the study marks the job finished.
#include "app/Study.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace bounce::study {

std::filesystem::path jobFolder(const Study& study, const Job& job);
std::filesystem::path recordPath(const Study& study, const Job& job);

// True when the job's record exists, parses and holds the job's current spec.
bool jobFinished(const Study& study, const Job& job);

// Runs the job (its inputs must be finished). A technique that refuses a scene (radiosity without
// area lights, ...) is not a failure: the record says "refused" with the reason.
Expected<void> runJob(const Study& study, const Job& job);

// This machine: host name, CPU model, cores; every record carries it (the report's machine line).
nlohmann::json hostJson();

}  // namespace bounce::study
