//! A model's parameters: `[parameters] NAME = { default, unit, domain, description }` or
//! `NAME = number`.

use toml::Spanned;
use tumble_scenarios::params::Domain;
use tumble_scenarios::toml_file;

use super::ModelFileError;
use super::decl::ParamDef;
use super::reader::{Src, domain};
use crate::units;

/// The parameter `name` declared by `value` (a table or a number), at `key`.
pub(super) fn read_parameter(
    src: &Src<'_>,
    key: &str,
    name: &Spanned<String>,
    value: &Spanned<toml::Value>,
) -> Result<ParamDef, ModelFileError> {
    Ok(match value.get_ref() {
        toml::Value::Table(t) => {
            for k in t.keys() {
                if !["default", "unit", "domain", "description"].contains(&k.as_str()) {
                    return Err(src.invalid(&value.span(), &format!("{key}.{k}"), "unknown key; a parameter takes `default`, `unit`, `domain` and `description`"));
                }
            }
            let Some(d) = t.get("default") else {
                return Err(src.invalid(&value.span(), key, "needs a `default` value"));
            };
            let default = toml_file::number_or_angle(d).map_err(|found| {
                src.invalid(
                    &value.span(),
                    &format!("{key}.default"),
                    format!("must be a number, found {found}"),
                )
            })?;
            let text_of = |k: &str| -> Result<String, ModelFileError> {
                match t.get(k) {
                    None => Ok(String::new()),
                    Some(toml::Value::String(s)) => Ok(s.clone()),
                    Some(other) => Err(src.invalid(
                        &value.span(),
                        &format!("{key}.{k}"),
                        format!("must be a string, found {}", toml_file::describe(other)),
                    )),
                }
            };
            let dom = text_of("domain")?;
            let domain = if dom.is_empty() {
                Domain::Finite
            } else {
                domain(&dom).ok_or_else(|| src.invalid(&value.span(), &format!("{key}.domain"), format!("unknown domain {dom:?}; write \"positive\", \"non-negative\", \"finite\" or \"non-zero\"")))?
            };
            let unit = text_of("unit")?;
            units::parse_unit(&unit)
                .map_err(|message| src.invalid(&value.span(), &format!("{key}.unit"), message))?;
            ParamDef {
                name: name.get_ref().clone(),
                default,
                unit,
                domain,
                description: text_of("description")?,
            }
        }
        _ => ParamDef {
            name: name.get_ref().clone(),
            default: src.number(key, value)?,
            unit: String::new(),
            domain: Domain::Finite,
            description: String::new(),
        },
    })
}
