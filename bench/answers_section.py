"""The answer-path section of docs/benchmarks.md: the robot's answers heard by the sender.

dtmf-bench-answers plays the robot's ACK to a frame the sender waits for through a room, one
answer per slot, alone and with the sender's own frames 20 dB louder across every answer (its
loudspeaker beside its microphone). One row per case, a column per profile.
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
      "ear gave an answer that answers that frame within its slot (with a key: a tag read with at most one tone "
      f"unheard and none wrong, within the guess budget of {first['guess_budget']} per transmission). "
      "\"own frames +20 dB\": one of the sender's frames sounds across every answer, from a chord before it to a "
      "chord after it, 20 dB louder, through the same room. Wrong: an answer taken for the slot's frame before the "
      "robot's answer to it began (an echo of an earlier answer, or noise); twice: a slot whose answer was read "
      "more than once (harmless: the sender stops waiting at the first); guesses: the most tagged readings that "
      "spelled another tag in one slot.")
    w("")
    w("| case | " + " | ".join(f"`{p}` heard (wrong, twice, guesses)" for p in shown) + " |")
    w("|---|" + "---|" * len(shown))
    for i, case in enumerate(first["cases"]):
        cells = []
        for p in shown:
            c = data[p]["answers"]["cases"][i]
            cells.append(f"{100 * c['heard_rate']:.2f} % of {c['answers']} ({c['wrong']}, {c['twice']}, "
                         f"{c['most_guesses']})")
        w(f"| {case['case']} | " + " | ".join(cells) + " |")
    w("")
