#!/usr/bin/env bash
# Builds mrloc with clang, AddressSanitizer + UndefinedBehaviorSanitizer (every finding
# fatal) and libFuzzer's coverage (not with MRLOC_FUZZ_COVERAGE=OFF) into build-asan/, and
# runs the whole test suite in it. CI
# calls this after the Release tests; scripts/fuzz.sh runs the fuzz targets of this build.
# Suppressions and their reasons: doc/hardening.md.
set -euo pipefail
cd "$(dirname "$0")/.."
# MRLOC_FUZZ_COVERAGE=OFF (CI): no libFuzzer coverage in mrloc's files (doc/hardening.md)
coverage="${MRLOC_FUZZ_COVERAGE:-ON}"
if [ ! -f build-asan/CMakeCache.txt ]; then
  # -O1: quicker to build than -O3, and sanitizer reports keep their line numbers.
  CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DMRLOC_SANITIZE=ON \
    -DMRLOC_FUZZ_COVERAGE="$coverage" >/dev/null
elif ! grep -q "^MRLOC_FUZZ_COVERAGE:BOOL=$coverage\$" build-asan/CMakeCache.txt; then
  cmake -S . -B build-asan -DMRLOC_FUZZ_COVERAGE="$coverage" >/dev/null
fi
cmake --build build-asan -j "$(nproc)" 2>&1 | { grep -v -E '^\[ *[0-9]+%\] (Building|Linking|Built)' || true; }
# LeakSanitizer off by default: see doc/hardening.md (ASAN_OPTIONS=detect_leaks=1 turns it on).
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=0:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:${UBSAN_OPTIONS:-}"
# Tests that only run whole scenarios again (Seed.*) skip here: the Release suite runs them.
export MRLOC_SANITIZED=1
cd build-asan
# The Monte Carlo tests that repeat, at length, code the rest of the suite runs sanitized
# (8 of the suite's 19 sanitized minutes, counted one test after another) are left to the
# Release suite unless MRLOC_SANITIZE_ALL=1, to keep CI under its 30 minutes (see
# doc/hardening.md).
long='MrlocOmnivision\.ErrorsMatchTheCovarianceOverTwentySeeds|MrlocFormation\.PixelModeMarch'
# 100 robots identified twice, 75 at 0.05 deg, 30 at 0.3 deg through 200 seeds, 100 seeded by
# a pair: the same search as the sanitized N = 50 and 75 scenes (75 seeded by a pair)
long+='|TriangleSearch\.AHundredRobotsAreLabelledWithNoWrongLabel|TriangleSearch\.SeventyFiveAtFiveHundredthsOfADegreeKeepNoWrongLabel|MrlocOmnivision\.SwarmOfAHundred.*'
long+='|TriangleSearch\.AChanceLayoutOfAFewRobotsIsNotKept|TriangleSearch\.AHundredRobotsWithACameraRangeArePairSeeded'
# a pixel march with the 27 camera starts: the EGL teardown it checks is the same sanitized
long+='|MrlocFormation\.APixelMarchCutShortWithCameraStartsExitsCleanly'
# formation's Table 1 in process and as a batch: the marches MrlocFormation runs sanitized
long+='|MrlocBatch\.FormationTableOneEqualsTheInProcessExperiment'
# a trial that is a whole run, beacon study included (83 s sanitized): the study and the run
# are sanitized by their own tests
long+='|MrlocTrial\.AMethodWithoutATrialOfItsOwnGivesTheRunsHeadline'
long+='|Elimination\.OfficeFloorOfTwentyFourIdenticalRooms|MrlocPolymap\.DrivingWithEveryAlgorithm'
long+='|MrlocFormation\.PatrolRoute|Visibility\.Star5000|Elimination\.FromNoisyScans'
long+='|FormationMarch\.ErrorDoesNotGrow|FormationAlgorithmOne\.ConvergesFromEveryStart'
long+='|Visibility\.RandomAndGeneratedMapsUpTo5000'
# the samples' tests simulate and localize five shipped scenarios again, whole
long+='|Samples\.EachIsWhatTheSimulatorMakesToday|Samples\.EachLocalizesWithItsIni'
# three of the five rawlog-mutation sweeps (265 s counted one after another); the beacons and
# polymap sweeps stay sanitized, and fuzz_rawlog fuzzes the same reader
long+='|Mutations\.FramesyncRawlogIsRefusedOrCountedNeverSilentlyTaken'
long+='|Mutations\.OmnivisionRawlogIsRefusedOrCountedNeverSilentlyTaken'
long+='|Mutations\.FormationRawlogIsRefusedOrCountedNeverSilentlyTaken|RealLogs\.BeaconTrackerOnMrclamDataset6'
# polymap's whole-map searches on a real log and on synthetic scans (the Release suite runs
# them; the sanitized suite runs the same code on localization_demo)
long+='|RealPolymap\.SenaLogOnIcpSlamsMapBesideIcpSlam|RealPolymap\.SenaLogOnMrptsBuildingMap'
long+='|ScanLocalizer\.ClutteredHalfTurnScan'
# twenty identical rooms, every layout and algorithm (Release; 2-5 rooms stay sanitized)
long+='|Elimination\.TwentyIdenticalRoomsEveryLayout|MrlocPolymap\.TwentyIdenticalRoomsEveryAlgorithmEnds'
# whole runs whose code other sanitized tests already cover, and checks of process behaviour
# (byte-identical repeats, folder locks, an interrupted re-run) that sanitizers add nothing to
long+='|MrlocPolymap\.RoomsWithPillarsLocalizeFromAGeneratedMapAndFromItsPolyFile'
long+='|MrlocPolymap\.PaperExperimentOnTheSteps76MapLocalizesFromEveryStart'
long+='|MrlocPolymap\.AFastRobotWithLongStepsIsFoundAtItsProbes|MrlocFramesync\.TeamOfFour'
long+='|FormationAlgorithmOne\.MidpointRuleConvergesWithBeaconsFacingAnyWay'
long+='|RunFolder\.AnInterruptedReRunLeavesThePreviousRunByteIdentical'
long+='|RunFolder\.ASecondMrlocOnTheSameFolderIsRefused|Samples\.MrptsRawlogEditReadsEachAsMrlocInfoDoes'
long+='|MrlocOmnivision\.ConventionalMethodAndByteIdenticalRepeats|MrlocRun\.SameIniAndSeedGiveByteIdenticalOutputs'
# the pixel experiment's marches (the pixel march's code stays sanitized in PixelMarch.NineMetres)
long+='|PixelMarch\.TableOneFromPixelsBeatsDeadReckoningAndRepeats'
# batch orchestration through GNU parallel (processes, folders, locks): the readers it uses
# are sanitized by fuzz_json_readers and MrlocBatch.AHostileBatchPlan, a trial by MrlocTrial.*
long+='|MrlocBatch\.(FramesyncSeedsAndSweeps|NoFolderNameOrPathIsCode|ResumeRunsOnlyWhatIsMissing|AJobCutShort|EmittedSlurmScript|HostsGetTheFolder)'
# a rawlog asking for gigabytes (the memory cap is the probe child's; ASan's allocator changes
# what it measures), thirty hostile labels end to end (the escaping is sanitized in Plots.* and
# HostileNames.InAnIni), every cost key's estimate (arithmetic the other Work.* tests run), and
# polymap's randomized draws from two seeds (the elimination is sanitized in Elimination.*)
long+='|BadRawlog\.CorruptSizeMeetsTheMemoryCap|HostileNames\.InARawlogsLabels'
long+='|Work\.TheCostKeysTheEstimateMissed|MrlocPolymap\.TheRunsSeedReachesTheRandomizedDraws'
# process behaviour again (a thread count that changes no result, byte-identical repeats, folder
# names and links, batch arguments) and MRPT's loader over every dataset (fuzz_rawlog fuzzes
# mrloc's reader); the polymap rawlog sweep (the beacons sweep stays sanitized)
long+='|MrlocCli\.ThreadsSetsTheExperimentsThreadsWithoutChangingTheirResults'
long+='|MrlocFramesync\.SameIniAndSeedGiveByteIdenticalRawlogsAndResults'
long+='|RunFolder\.OutFoldersThatCouldRunOrEscapeAreTakenLiterallyOrRefused'
long+='|MrlocBatch\.(BadArgumentsAreRefusedBeforeAnythingIsWritten|LinksInABatchFolderAreRefusedAndItsLockIsHeld)'
long+='|MrptData\.InfoAgreesWithMrptsLoaderOnEveryDataset|Mutations\.PolymapRawlogIsRefusedOrCountedNeverSilentlyTaken'
# every method's trials over several seeds, whole runs again (15 s in Release): a trial's code
# is sanitized by MrlocTrial.OneLineDeterministicPerSeed and each method's own runs
long+='|MrlocTrial\.EveryMethodsTrialsDifferFromSeedToSeed'
# process behaviour again (byte-identical repeats, a used folder, a failed run's exit code),
# MRPT's own INI on the log RealPolymap.LocalizationDemoBesidePfLocalization runs sanitized,
# and sweeps whose code the rest of their suite runs sanitized (the overlay against sampling,
# the detector over many positions, identical rooms with pillars besides those without)
long+='|MrlocFormation\.SameIniAndSeedGiveByteIdenticalRawlogs|MrlocCli\.ARunIntoAUsedFolder'
long+='|RealPolymap\.AScanThatFitsNoPlaceOfTheMapIsAFailedRunExitThree|RealPolymap\.MrptsPfLocalizationIniRunsUnchanged'
long+='|Overlay\.StepsMapTwelveHypothesesAgainstSampling|MarkerDetector\.AMarkerOffAViewsAxisHasNoBias'
long+='|Elimination\.IdenticalRoomsWithPillarsEveryLayoutEveryAlgorithm'
# issue 54: five formats imported and localized twice each (the import and localize paths are
# sanitized by Import.* and the methods' own runs; the time rule by BadRawlog.AStampBefore1970),
# and a 300 s simulated run (the particle start-up's code is sanitized in ParticleStart.*)
long+='|Import\.EveryFormatFromTimeZeroLocalizes|FirstContact\.OneBeaconAtATime'
# issue 55 (CI at 1,630 s of its 1,800): the beacons rawlog-mutation sweep (28 s sanitized;
# fuzz_rawlog fuzzes the reader, the tracker is sanitized by BeaconTracker.* and ParticleStart.*),
# a pixel march without tags (the pixel march stays sanitized in PixelMarch.NineMetres), the
# beacon reports per scheduling (whole runs and pictures: MrlocRun.BeaconStudy* stays), and two
# polymap runs whose code the elimination and hypotheses tests sanitize (narrow passages,
# features below the tolerance)
long+='|Mutations\.BeaconsRawlogIsRefusedOrCountedNeverSilentlyTaken'
long+='|MrlocFormation\.AMarchWhoseCamerasFindNoTagSaysSoInTheHeadline'
long+='|MrlocRun\.BeaconReportsShowTheDistanceBetweenFixesPerScheduling'
long+='|MrlocPolymap\.IdenticalRoomsBehindNarrowPassagesSayWhy|MrlocPolymap\.FeaturesBelowTheScansTolerance'
# the shafts map's whole run (4 s here): its eliminations are the steps maps' code
# (Elimination.StepsMaps*), PolymapFiles.TheTableSaysWhereEachAlgorithmParts* its table note
long+='|MrlocPolymap\.StepsJoinedByShaftsRunsThePapersTables'
# the exact pipeline on MRPT's two building maps (six whole runs, 6 s here): the trace's
# opening and the consensus pass run sanitized in FreeSpaceTrace.* and Hypotheses.Corners*
long+='|RealPolymap\.ExactPipelineOnMrptsTracedBuildingMaps'
# issue 57 (CI at 1,871 s of its 1,800): whole runs whose code the rest of the sanitized suite
# runs (a driven polymap run: MrlocPolymap.DrivingRobot's eliminations are Elimination.*'s; the
# obstacle march: MrlocFormation's other runs; the corridor: MrlocFramesync.WithoutSharing runs
# the same run; identical rooms: Elimination.StepsMaps* and the shafts; the map-size sweep;
# the paper's room study twice: MrlocRun.BeaconStudy* runs it), and the command line's
# checks of help texts, completion, hints, folder names and the install rules (process
# behaviour; the MRPT-keys warning stays sanitized)
long+='|MrlocPolymap\.DrivingRobotEliminatesAndLocalizeReplaysIt'
long+='|MrlocFormation\.ObstacleRunKeepsEveryRobotOutOfTheSafetyZonesAndArrives'
long+='|MrlocFramesync\.CorridorRunSharesTheFrameAndTheReportShowsThePapersMeasure'
long+='|Elimination\.IdenticalRoomsEveryLayoutEveryAlgorithm|MrlocPolymap\.SweepOverMapSizesDrawsFigsSixAndSeven'
long+='|BeaconStudy\.ThePapersRoomStudyMeetsTheGoalAndIsDeterministic'
long+='|CommandLine\.(EveryCommand|VersionUnknown|BashCompletion|SimulateAndLocalize|AnIniWithoutAName|CmakeInstall)'
# and (CI at 1,606 s here with the above) five rendered panoramas end to end (the renderer and
# the detector run sanitized in tests/omnivision), a sweep of ray casts against the
# visibility polygons (Visibility's other cases stay), the shafts map's eliminations (the
# same code as Elimination.StepsMaps*), thirty robots end to end (TriangleSearch.* runs the
# search in process), bad formation and polymap keys (the key tables' checks, sanitized by
# MrlocErrors.* and fuzz_ini) and crafted provenance files (path checks: RunFolder's others)
long+='|MrlocOmnivision\.FiveRobotsFromRenderedPanoramas|Visibility\.HolesAgreeWithRayCasting'
long+='|Elimination\.StepsJoinedByShafts|MrlocOmnivision\.SwarmOfThirty'
long+='|MrlocFormation\.BadFormationInput|MrlocPolymap\.BadPolymapInput'
long+='|RunFolder\.ACraftedProvenanceOrSymlinks'
# and (CI at 1,641 s here with those) two identical rooms told apart by a corridor (the scan
# localizer runs sanitized in RealPolymap.LocalizationDemoBesidePfLocalization), MRPT's
# range-only INIs with real times (MrptData.UwbDemoAgainstItsGroundTruthFile stays), rooms
# behind narrow passages (Elimination's steps maps stay), the Udacity log in two halves
# (RealSonar.UdacityWallsFromRealEchoes stays) and where MRPT's ground truth is found (a file
# lookup)
long+='|ScanLocalizer\.TwoIdenticalRooms|MrptData\.RangeOnlyInisRunUnchanged'
long+='|Elimination\.RoomsBehindPassagesTooNarrow|RealSonar\.TwoHalvesOfTheUdacityLog'
long+='|FrontDoor\.MrptGroundTruthIsPickedUp'
# searches that repeat, exhaustively, code the other sanitized tests of their kind run (the
# multilateration, elimination and verification-tour tests of tests/beacons, tests/polymap)
long+='|Multilateration\.MonteCarloRmseWithinTenPercentOfCramerRao'
long+='|Elimination\.StepsMapsEveryStartEveryStrategy|TravelBounds\.TourIsTheExhaustiveOptimum'
# every shipped INI's whole run checked picture by picture: the renderers run sanitized in
# TopView.* and Plots.*, the runs in the methods' own end-to-end tests
long+='|Pictures/EveryShippedIni\.'
# issue 58: omnivision's swarm twice, to its t_b search (the search runs sanitized in
# Methods.Localized*)
long+='|MrlocOmnivision\.LocalizedSearchAtTbGivesThePapersSolution'
if [ "${MRLOC_SANITIZE_ALL:-0}" = 1 ]; then
  ctest --output-on-failure -j "$(nproc)" "$@"
else
  ctest --output-on-failure -j "$(nproc)" -E "$long" "$@"
fi
