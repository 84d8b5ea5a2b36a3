"""The teaching session: a state machine from teacher lines to replies, its command table,
message catalogue, journal, store of files and the composition root that builds it."""
