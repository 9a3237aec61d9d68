"""SQLite atlases: grid files, grid runs, the --where language, exports and the static web site."""
