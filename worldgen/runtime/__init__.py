"""The runtime of students' nodes: which package provides each module they import (:mod:`.table`), what a node
imports (:mod:`.imports`, read without running it), whether the Python that runs the nodes finds it
(:mod:`.check`, the preflight of ``run`` and ``drive``), and ``worldgen doctor`` (:mod:`.doctor`)."""
