"""The worlds a session teaches in, behind one protocol (``teach.world.protocol``)."""
