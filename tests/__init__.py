"""The test suite (a package, so the oracles import as ``tests.oracles``)."""
