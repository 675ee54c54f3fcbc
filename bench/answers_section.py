"""The answer-path section of docs/benchmarks.md: the robot's answers heard by the sender.

dtmf-bench-answers plays the robot's ACK to a frame the sender waits for through a room, one
answer per slot, alone and beside the sender's own frames from its loudspeaker 0.1 m from its
microphone. One row per case, a column per profile.
"""


def answers_section(w, data, profiles, ok):
    w("## Answer path")
    w("")
    shown = [p for p in profiles if ok(data[p]["answers"])]
    if not shown:
        w("Not run: " + "; ".join(f"{p}: {data[p]['answers']['error']}" for p in profiles))
        w("")
        return
    first = data[shown[0]]["answers"]
    # A slot holds one answer and the ear's lockout after it (the seed's ear locks 900 ms).
    slots = ", ".join(f"`{p}` {data[p]['answers']['slot_ms']:.0f} ms" for p in shown)
    w(f"`dtmf-bench-answers`: the robot's ACK to a random command's frame the sender waits for (planned one after "
      f"another, so numbered consecutively and answered in alternate reply lanes), {first['answers_per_case']} per "
      f"case, one per slot ({slots}: the round trip's cadence, so each answer meets the last one's tail), through the case's room to the sender's ear; heard means the "
      "ear gave an answer that answers that frame within its slot (with a key: a tag chord with 9 of its 16 bands "
      "right, no budget). \"own loudspeaker 0.1 m\": the sender's own frames through the same room from 0.1 m "
      "(its direct sound 20 dB over the answer's, its reverberation the room's: docs/protocol.md §7); unkeyed, one "
      "of them sounds across every answer, from a chord before it to a chord after it; keyed, the frame answered, "
      "ending 2–22 ms before its tag chord begins, as the robot answers. Wrong: an answer taken for the slot's "
      "frame before the robot's answer to it began (an echo of an earlier answer, or noise); twice: a slot whose "
      "answer was read more than once (harmless: the sender stops waiting at the first); stray: the most tag "
      "chord readings in one slot that answered nothing.")
    w("")
    w("| case | " + " | ".join(f"`{p}` heard (wrong, twice, stray)" for p in shown) + " |")
    w("|---|" + "---|" * len(shown))
    for i, case in enumerate(first["cases"]):
        cells = []
        for p in shown:
            c = data[p]["answers"]["cases"][i]
            cells.append(f"{100 * c['heard_rate']:.2f} % of {c['answers']} ({c['wrong']}, {c['twice']}, "
                         f"{c['most_stray']})")
        w(f"| {case['case']} | " + " | ".join(cells) + " |")
    w("")
