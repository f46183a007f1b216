#include "app/StudyRun.h"

#include "app/SweepJobs.h"
#include "core/FileIo.h"

#include <nlohmann/json.hpp>

#include <set>

namespace bounce::study {

namespace fs = std::filesystem;
using nlohmann::json;

Expected<void> writeStudyCopy(const Study& s) {
    std::error_code ec;
    fs::create_directories(s.output, ec);
    if (ec) return makeError("--out {}: cannot create the folder: {}", s.output.string(), ec.message());
    BOUNCE_TRY(const std::string text, readTextFile(s.file));
    json jobs = json::array();
    for (const Job& j : s.jobs)
        jobs.push_back({{"id", j.id}, {"kind", jobKindName(j.kind)}, {"stage", j.stage}, {"inputs", j.inputs}});
    const json copy = {{"name", s.name}, {"file", s.file.string()}, {"study", json::parse(text)}, {"jobs", jobs}};
    return writeTextFileAtomic(s.output / "study.json", copy.dump(2) + "\n");
}

Expected<InProcessRun> runStudyInProcess(const Study& study, const JobCallback& before) {
    BOUNCE_TRY_VOID(writeStudyCopy(study));
    InProcessRun run;
    run.jobs = study.jobs.size();
    std::vector<const Job*> pending;
    for (const Job& j : study.jobs) {
        if (jobFinished(study, j)) ++run.finishedBefore;
        else pending.push_back(&j);
    }
    // study.jobs lists stage 1 before stage 2, so this order runs every input before its readers.
    std::set<std::string> failed;
    for (size_t i = 0; i < pending.size(); ++i) {
        const Job& j = *pending[i];
        bool inputFailed = false;
        for (const std::string& in : j.inputs) inputFailed |= failed.count(in) > 0;
        if (inputFailed) {
            ++run.blocked;
            failed.insert(j.id);
            continue;
        }
        if (before) before(j, i, pending.size());
        if (auto r = runJob(study, j); !r) {
            failed.insert(j.id);
            run.failed.push_back(j.id + ": " + r.error().message);
            continue;
        }
        ++run.ran;
    }
    for (const Job& j : study.jobs) {
        auto text = readTextFile(recordPath(study, j));
        if (!text) continue;
        const json record = json::parse(*text, nullptr, /*allow_exceptions=*/false);
        if (record.is_object() && record.value("status", "ok") != "ok") ++run.refused;
    }
    return run;
}

}  // namespace bounce::study
