"""Number new inline rows after the rows there are, so "Add another" keeps their order."""

from django.db.models import Max
from django.forms.models import BaseInlineFormSet


class PositionedFormSet(BaseInlineFormSet):
    """An inline formset whose new rows, left at the default position, come last.

    Each new row whose position the researcher did not type gets the next number after
    the parent's rows (saved ones and those added before it, in the form's order); a
    typed position, negative ones included, is kept.
    """

    def save_new_objects(self, commit=True):
        self._next_position = None
        return super().save_new_objects(commit)

    def save_new(self, form, commit=True):
        if "position" in form.fields and "position" not in form.changed_data:
            form.instance.position = self._position_after_the_rest()
        return super().save_new(form, commit)

    def _position_after_the_rest(self) -> int:
        if self._next_position is None:
            rows = self.model._default_manager.filter(**{self.fk.name: self.instance})
            last = rows.aggregate(last=Max("position"))["last"]
            self._next_position = 0 if last is None else last + 1
        position = self._next_position
        self._next_position += 1
        return position
