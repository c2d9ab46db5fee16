"""Test reading segmentations (seed 001 Code 3.1 and §5.2.1), and that bad ones say why."""

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from synthesis.transitions import Segment, SegmentationError, check_segmentation, parse_segmentation

# Seed 001 Code 3.1, sentence frase1 (the interpreter element renamed): the seed's own
# layout, one element per segment named by its sign.
ORIGINAL = """<Daniele><frase1>
  <Intro end="235" pos="1" start="0" word="False"/>
  <TRANSITION1 end="292" pos="2" start="236" word="False"/>
  <Ola end="355" pos="3" start="293" word="True"/>
  <TRANSITION2 end="424" pos="4" start="356" word="False"/>
  <meu_Nome end="473" pos="5" start="425" word="True"/>
</frase1></Daniele>"""
PROPOSED = """<sseg version="1.0" interpreter="A"><sentence number="1">
  <segment type="sign" order="1" start="0" end="40" label="HELLO"/>
  <segment type="transition" order="2" start="41" end="60"/>
  <segment type="sign" order="3" start="61" end="100" label="NAME"/>
</sentence></sseg>"""
JSON = json.dumps(
    {
        "sentences": [
            {
                "number": 1,
                "segments": [
                    {"type": "sign", "order": 1, "start": 0, "end": 40, "label": "HELLO"},
                    {"type": "transition", "order": 2, "start": 41, "end": 60},
                    {"type": "sign", "order": 3, "start": 61, "end": 100, "label": "NAME"},
                ],
            }
        ]
    }
)


def test_the_seeds_original_layout_reads_into_signs_transitions_and_rest():
    (sentence,) = parse_segmentation(ORIGINAL)
    assert sentence.sentence == "frase1"
    assert [s.kind for s in sentence.segments] == [
        "rest",
        "transition",
        "sign",
        "transition",
        "sign",
    ]
    (before, transition, after) = sentence.transitions()[0]
    assert (before.label, transition.label, after.label) == ("Ola", "TRANSITION2", "meu_Nome")
    assert transition.n_frames == 424 - 356 + 1


@pytest.mark.parametrize("text", [PROPOSED, JSON], ids=["xml", "json"])
def test_the_proposed_xml_and_json_read_alike(text):
    (sentence,) = parse_segmentation(text)
    assert sentence.segments[1] == Segment("transition", 2, 41, 60, "")
    assert len(sentence.transitions()) == 1


@pytest.mark.parametrize(
    ("text", "message"),
    [
        # Seed 001 Code 3.1, frase2: TRANSITION4 starts on the frame bonito ends on.
        (
            '<D><frase2><bonito end="624" pos="7" start="509" word="True"/>'
            '<TRANSITION4 end="661" pos="8" start="624" word="False"/></frase2></D>',
            "orders must be 1 to 2",
        ),
        (
            '<D><frase2><bonito end="624" pos="1" start="509" word="True"/>'
            '<TRANSITION4 end="661" pos="2" start="624" word="False"/></frase2></D>',
            "segment 2 (TRANSITION4) starts at frame 624, within segment 1 (bonito), which "
            "ends at 624",
        ),
        (
            PROPOSED.replace('start="61" end="100"', 'start="101" end="100"'),
            "segment 3 (NAME) starts at frame 101, after its end 100",
        ),
        (PROPOSED.replace('order="3"', 'order="2"'), "without gaps or repeats"),
        (PROPOSED.replace('type="transition"', 'type="pause"'), "type 'pause' is not one of"),
        (PROPOSED.replace('end="60"', 'end="six"'), "end is not a whole number: 'six'"),
        (PROPOSED[:-20], "Not well-formed XML"),
        (
            '{"sentences": [{"segments": '
            '[{"type": "sign", "order": true, "start": 0, "end": 1}]}]}',
            "order is not a whole number: True",
        ),
        ('{"sentences": 3}', 'an object with a "sentences" list'),
        ("", "empty"),
    ],
)
def test_bad_segmentations_say_what_is_wrong(text, message):
    with pytest.raises(SegmentationError, match=message.replace("(", r"\(").replace(")", r"\)")):
        parse_segmentation(text)


def test_a_segment_past_the_recordings_end_is_named():
    (sentence,) = parse_segmentation(PROPOSED)
    check_segmentation(sentence, n_frames=101)
    with pytest.raises(
        SegmentationError, match="ends at frame 100, but the recording's last frame is 89"
    ):
        check_segmentation(sentence, n_frames=90)


@settings(max_examples=300, deadline=None)
@given(
    base=st.sampled_from([PROPOSED, JSON, ORIGINAL]),
    cut=st.integers(0, 400),
    insert=st.text(max_size=8),
    drop=st.integers(0, 8),
)
def test_mangled_files_are_read_or_refused_never_crash(base, cut, insert, drop):
    """Fuzz: a damaged file either reads or raises SegmentationError, nothing else."""
    cut = min(cut, len(base))
    text = base[:cut] + insert + base[cut + drop :]
    try:
        sentences = parse_segmentation(text)
    except SegmentationError:
        return
    for sentence in sentences:
        check_segmentation(sentence)  # what reads is consistent
