"""Running work units: inline, a process pool or Dask; checkpoints; progress; sizes and times in words.

A service under the synthesis floor: it imports the chain types and nothing above them."""
