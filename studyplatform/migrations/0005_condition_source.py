"""Keep the meaning of word conditions saved before techniques were registered.

Until then every fingerspelled word's Variable, Constant, Normalized and Motion capture
clips retimed one simulated performance, whatever the condition said; the technique
registry makes that an explicit parameter (``source``) whose default is the engine's
alphabet. Conditions that relied on the old behaviour get ``"source": "simulated"``
written out, so they render exactly as before.
"""

from django.db import migrations

# The timings of that time (a migration keeps its own copy of what it meant then).
RETIMED = {"variable", "constant", "normalized", "mocap"}


def spell_out_source(apps, schema_editor):
    Condition = apps.get_model("studyplatform", "Condition")
    for condition in Condition.objects.filter(study__items__kind="word").distinct():
        parameters = dict(condition.parameters or {})
        if parameters.get("timing") in RETIMED and "source" not in parameters:
            parameters["source"] = "simulated"
            Condition.objects.filter(pk=condition.pk).update(parameters=parameters)


class Migration(migrations.Migration):
    dependencies = [("studyplatform", "0004_study_shared_computer")]

    operations = [migrations.RunPython(spell_out_source, migrations.RunPython.noop)]
