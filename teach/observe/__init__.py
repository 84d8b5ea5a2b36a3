"""Everything that watches a session: the observer hook, and the rerun recording (writer,
scene, reader, viewer) behind it. rerun is imported in this package only."""
