"""Voice: the robot speaks (espeak-ng) and hears English (pocketsphinx), offline.

One module owns each outside library: ``synth`` espeak-ng (through espeakng-loader),
``recognise`` pocketsphinx, ``device`` the sound devices (sounddevice). Nothing here is
imported unless voice is asked for, so a session without ``--voice`` starts as fast as before.
"""
