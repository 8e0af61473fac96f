"""What a person looks at: the top-down picture of a world (``preview``), and the self-contained 3D pages of a
world, of a run replayed, and of a class's grades (``page``, ``replay``, ``index``), with three.js vendored from the
npm registry at build time (``vendor``)."""
