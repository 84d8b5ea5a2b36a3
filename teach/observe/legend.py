"""What the tree views' symbols and colours mean, in the session's language (the viewer's Legend tab)."""

from __future__ import annotations

_LEGEND = {
    "en": """# How to read the trees

**Tree that ran**: the behaviour tree the robot ran, coloured by the tick under the time cursor.
Between ticks (and outside runs) it is grey: no colour is left over from another tick. A tree too
large to read whole shows the nodes the tick reached; `… 27 nodes` stands for 27 it did not reach.

**Current generation**: what the robot has learned so far, as saved in `trees/`.

| symbol | node | what it does |
|---|---|---|
| `?` | fallback | tries its children from left to right until one succeeds |
| `→` | sequence | runs its children from left to right while they succeed |
| `⇉ k/n` | parallel | runs all its children; succeeds when k of the n succeed |
| `◇` | inverter | turns its child's success into failure and back |
| `…?` | condition | a question about the world: succeeds when the answer is yes |
| `▶ …` | action | the action the robot is doing at this tick |
| `… 27 nodes` | folded | 27 nodes this tick did not reach, drawn as one |

| colour | status at this tick |
|---|---|
| 🟢 green | success |
| 🔴 red | failure |
| 🟠 orange | running |
| ⚪ grey | not ticked |
""",
    "de": """# So liest man die Bäume

**Ausgeführter Baum**: der Verhaltensbaum, den der Roboter ausgeführt hat, gefärbt nach dem Tick
unter dem Zeitcursor. Zwischen Ticks (und außerhalb von Läufen) ist er grau: keine Farbe bleibt
von einem anderen Tick stehen. Ein Baum, der ganz zu groß zum Lesen wäre, zeigt die Knoten, die der
Tick erreicht hat; `… 27 Knoten` steht für 27, die er nicht erreicht hat.

**Aktuelle Generation**: was der Roboter bisher gelernt hat, wie in `trees/` gespeichert.

| Symbol | Knoten | was er tut |
|---|---|---|
| `?` | Fallback | probiert seine Kinder von links nach rechts, bis eines gelingt |
| `→` | Sequenz | führt seine Kinder von links nach rechts aus, solange sie gelingen |
| `⇉ k/n` | Parallel | führt alle Kinder aus; gelingt, wenn k der n gelingen |
| `◇` | Inverter | macht aus dem Erfolg seines Kindes einen Fehlschlag und umgekehrt |
| `…?` | Bedingung | eine Frage an die Welt: gelingt, wenn die Antwort ja ist |
| `▶ …` | Aktion | die Aktion, die der Roboter in diesem Tick ausführt |
| `… 27 Knoten` | zusammengefaltet | 27 Knoten, die dieser Tick nicht erreicht hat, als einer gezeichnet |

| Farbe | Status in diesem Tick |
|---|---|
| 🟢 grün | Erfolg |
| 🔴 rot | Fehlschlag |
| 🟠 orange | läuft |
| ⚪ grau | nicht getickt |
""",
}


def legend_document(lang: str) -> str:
    """The legend in ``lang`` (English for a language it does not know)."""
    return _LEGEND.get(lang, _LEGEND["en"])
