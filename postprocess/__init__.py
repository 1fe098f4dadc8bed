"""Post-processing of the scenes' outputs (numpy; matplotlib for the figures), in layers, each
module importing only from the layers below it:

1. what a point directory holds and the quantities measured in it: rundir (a point's files,
   what completed, failed and running mean; standard library only, the sweep runner imports it
   too), quantities (the table: name, label, unit, the files each comes from), scenes,
   selection (the frictional steady-part rule), signals
2. readers: io (every file of a point, each problem a DataError naming the file)
3. one run measured: observables, durations
4. the run record and its loaders: record (RunRecord), summary (the summary file), runs
   (load_runs, from raw outputs or summaries)
5. analyses across runs: study, reference (claims.csv), limit, transition
6. presentation: figures, formatting
7. one writer per command: write_report, write_limit, write_compare, write_transition,
   write_summaries; __main__ parses the command line and calls one of them."""
