#pragma once
// The steps a run folder is made of (simulate, localize with the method's experiment,
// report), each writing into a folder it is given, and the transaction that puts a command's
// steps into the run folder all at once (common::RunTransaction). Below the commands:
// `simulate`, `localize`, `report`, `run` and `trial` are each a few of these in a row.
#include <mrloc/common/Error.h>
#include <mrloc/common/Log.h>
#include <mrloc/common/Outcome.h>
#include <mrloc/common/RunTransaction.h>
#include <mrloc/method/Registry.h>

#include <string>

#include "RunSetup.h"

namespace mrloc::app {

/** Refuses work beyond the budget before anything is written (method::checkWork, with the
 *  process's thread count); announces long work unless `quiet`. */
void checkWorkOf(const Setup& s, bool simulating, bool localizing, bool quiet);

/** Simulates the setup's scenario into `dir`; returns the rawlog's path. */
std::string simulateStep(Setup& s, const std::string& dir, const common::Log& log);

/** Localizes `rawlog` into `dir` and runs the method's experiment; writes metrics.json with
 *  the method's headline, which it returns. `rawlogShownAs`: the rawlog's path as
 *  metrics.json records it (the run folder's, not the staging folder's, for a rawlog the
 *  same command simulated). */
common::Headline localizeStep(const method::Registry& registry, Setup& s, const std::string& rawlog,
                              const std::string& dir, const common::Log& log,
                              const std::string& rawlogShownAs);

/** report.html and its pictures of the run folder `dir`; returns the page's path. */
std::string reportStep(const method::Registry& registry, const std::string& dir);

/** Simulates the setup's scenario into `dir`, localizes it and runs the method's experiment,
 *  quietly, as `mrloc run` does without its report: `mrloc trial` of a method that registers
 *  no trial of its own (its headline holds its experiment's figures). */
common::Headline simulateAndLocalize(const method::Registry& registry, Setup& s,
                                     const std::string& dir);

/** Runs `steps(staging)` as `step` of the run folder `dir`: they write into a staging copy
 *  of it, which replaces `dir` only when they all returned. An mrloc::Error from them is
 *  rethrown with the staging folder's paths written as `dir`'s, after `context`. */
template <class Steps>
void inTransaction(const std::string& dir, const std::string& step, const common::Log& log,
                   Steps&& steps, const std::string& context = "") {
    common::RunTransaction tx(dir, step, log);
    try {
        steps(tx.staging());
        tx.commit();
    } catch (const Error& e) {
        throw Error(context + tx.inFolderTerms(e.what()));
    }
}

}  // namespace mrloc::app
